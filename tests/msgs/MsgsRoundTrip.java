// The Java round trip of meshtopo's LCM types (ctest msgs.java_round_trip):
// each sample NAME.TYPE.lcmbin that msgs_write_samples encoded in C is decoded
// with the generated class meshtopo.TYPE from meshtopo-msgs.jar and encoded
// again, which must give the same bytes; every type listed in types.txt must
// have a sample, and bytes of one type must not decode as another.
// usage: java -cp lcm.jar:meshtopo-msgs.jar:CLASSES MsgsRoundTrip DIR

import java.io.ByteArrayOutputStream;
import java.io.DataOutputStream;
import java.io.IOException;
import java.lang.reflect.InvocationTargetException;
import java.nio.file.DirectoryStream;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.Paths;
import java.util.ArrayList;
import java.util.Collections;
import java.util.List;
import java.util.Set;
import java.util.TreeSet;
import lcm.lcm.LCMEncodable;

public class MsgsRoundTrip {
    static LCMEncodable decode(String type, byte[] bytes) throws Exception {
        Class<?> cls = Class.forName("meshtopo." + type);
        try {
            return (LCMEncodable) cls.getConstructor(byte[].class).newInstance((Object) bytes);
        } catch (InvocationTargetException e) {
            if (e.getCause() instanceof Exception) throw (Exception) e.getCause();
            throw e;
        }
    }

    static byte[] encode(LCMEncodable msg) throws IOException {
        ByteArrayOutputStream out = new ByteArrayOutputStream();
        msg.encode(new DataOutputStream(out));
        return out.toByteArray();
    }

    public static void main(String[] args) throws Exception {
        if (args.length != 1) {
            System.err.println("usage: MsgsRoundTrip DIR");
            System.exit(2);
        }
        Path dir = Paths.get(args[0]);
        List<String> types = new ArrayList<>();
        for (String line : Files.readAllLines(dir.resolve("types.txt")))
            if (!line.isEmpty()) types.add(line);
        List<Path> files = new ArrayList<>();
        try (DirectoryStream<Path> found = Files.newDirectoryStream(dir, "*.lcmbin")) {
            for (Path p : found) files.add(p);
        }
        Collections.sort(files);

        int failures = 0;
        Set<String> seen = new TreeSet<>();
        for (Path file : files) {
            String name = file.getFileName().toString();  // NAME.TYPE.lcmbin
            String[] parts = name.split("\\.");
            String type = parts[parts.length - 2];
            byte[] bytes = Files.readAllBytes(file);
            byte[] again = encode(decode(type, bytes));
            int differs = -1;
            for (int i = 0; i < Math.max(bytes.length, again.length); i++) {
                if (i >= bytes.length || i >= again.length || bytes[i] != again[i]) {
                    differs = i;
                    break;
                }
            }
            if (differs >= 0) {
                System.out.printf("FAIL %s: %d bytes in, %d out, first difference at byte %d%n",
                                  name, bytes.length, again.length, differs);
                failures++;
            } else {
                System.out.printf("ok   %s (meshtopo.%s, %d bytes)%n", name, type, bytes.length);
            }
            seen.add(type);

            for (String other : types) {
                if (other.equals(type)) continue;
                try {
                    decode(other, bytes);
                    System.out.printf("FAIL %s decodes as meshtopo.%s%n", name, other);
                    failures++;
                } catch (IOException expected) {
                    // bad fingerprint
                }
            }
        }
        for (String type : types) {
            if (!seen.contains(type)) {
                System.out.printf("FAIL no sample of meshtopo.%s%n", type);
                failures++;
            }
        }
        System.out.printf("%d files, %d types, %d failures%n", files.size(), seen.size(), failures);
        System.exit(failures == 0 ? 0 : 1);
    }
}
