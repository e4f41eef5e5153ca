/* `meshtopo spy`: starts lcm-spy with the meshtopo message types on its class
 * path, so every message on the bus is shown decoded. Runs
 * `java -cp lcm.jar:jchart2d.jar:meshtopo-msgs.jar lcm.spy.Spy` itself (no
 * -Xincgc, which OpenJDK 17 refuses) by exec: this process becomes lcm-spy.
 * Each missing piece (java, lcm.jar, jchart2d.jar, the message jar) is named
 * with its Debian package before anything is started. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "remote.h"

/* The environment variable naming the message jar (overrides the paths below). */
#define SPY_ENV_MSGS_JAR "MESHTOPO_MSGS_JAR"

/* Set by tools/CMakeLists.txt: the jar in the build tree, where it is
 * installed, and the lcm.jar it was compiled against. */
#ifndef MESHTOPO_MSGS_JAR_BUILD
#define MESHTOPO_MSGS_JAR_BUILD ""
#endif
#ifndef MESHTOPO_MSGS_JAR_INSTALLED
#define MESHTOPO_MSGS_JAR_INSTALLED "/usr/local/share/java/meshtopo-msgs.jar"
#endif
#ifndef MESHTOPO_MSGS_JAR_FROM_BINDIR
#define MESHTOPO_MSGS_JAR_FROM_BINDIR "../share/java/meshtopo-msgs.jar"
#endif
#ifndef MESHTOPO_LCM_JAR
#define MESHTOPO_LCM_JAR "/usr/share/java/lcm.jar"
#endif
#ifndef MESHTOPO_JCHART2D_JAR
#define MESHTOPO_JCHART2D_JAR "/usr/share/java/jchart2d.jar"
#endif

enum { SPY_PATH_MAX = 4096 };

static const cli_option options[] = {
    {"lcm-url", "URL", "LCM provider URL (default: $" CLI_ENV_LCM_URL ", else LCM's own)"},
};

/* Looks `name` up in $PATH like execvp does; writes the first executable
 * match into out. */
static bool path_find(const char *name, char *out, size_t size)
{
    const char *path = getenv("PATH");
    if (!path || !path[0]) path = "/usr/local/bin:/usr/bin:/bin";
    while (*path) {
        const char *end = strchr(path, ':');
        size_t len = end ? (size_t)(end - path) : strlen(path);
        /* An empty entry means the current directory. */
        int n = len ? snprintf(out, size, "%.*s/%s", (int)len, path, name)
                    : snprintf(out, size, "./%s", name);
        if (n > 0 && (size_t)n < size && access(out, X_OK) == 0) return true;
        if (!end) break;
        path = end + 1;
    }
    return false;
}

static bool file_readable(const char *path)
{
    return path[0] && access(path, R_OK) == 0;
}

/* The message jar: $MESHTOPO_MSGS_JAR when set (and then nothing else), else
 * the build tree's, else the one installed with this program, else the one
 * at the configured prefix. NULL after printing what was looked for. */
static const char *msgs_jar_find(void)
{
    static char beside[SPY_PATH_MAX];
    const char *env = getenv(SPY_ENV_MSGS_JAR);
    if (env && env[0]) {
        if (file_readable(env)) return env;
        cli_error("spy", "$%s names %s, which cannot be read: %s", SPY_ENV_MSGS_JAR, env,
                  strerror(errno));
        return NULL;
    }
    if (file_readable(MESHTOPO_MSGS_JAR_BUILD)) return MESHTOPO_MSGS_JAR_BUILD;
    /* the jar installed with this program */
    if (cli_beside_program(MESHTOPO_MSGS_JAR_FROM_BINDIR, beside, sizeof beside) &&
        file_readable(beside))
        return beside;
    if (file_readable(MESHTOPO_MSGS_JAR_INSTALLED)) return MESHTOPO_MSGS_JAR_INSTALLED;
    cli_error("spy",
              "meshtopo-msgs.jar (the message types for lcm-spy) not found: looked at "
              "%s%s%s; build it with a JDK and lcm.jar present (Debian: default-jdk-headless "
              "liblcm-java), install it, or set $%s",
              MESHTOPO_MSGS_JAR_BUILD[0] ? MESHTOPO_MSGS_JAR_BUILD : "",
              MESHTOPO_MSGS_JAR_BUILD[0] ? " and " : "", MESHTOPO_MSGS_JAR_INSTALLED,
              SPY_ENV_MSGS_JAR);
    return NULL;
}

static int run_spy(const cli_args *args)
{
    const char *url = cli_arg(args, "lcm-url");
    if (!url) url = getenv(CLI_ENV_LCM_URL);
    if (url && !url[0]) url = NULL;

    char java[SPY_PATH_MAX];
    if (!path_find("java", java, sizeof java)) {
        cli_error("spy",
                  "java not found on PATH; lcm-spy needs a Java runtime with AWT "
                  "(Debian: default-jre)");
        return CLI_EXIT_READ;
    }
    if (!file_readable(MESHTOPO_LCM_JAR)) {
        cli_error("spy", "%s (LCM for Java, lcm-spy itself) not found (Debian: liblcm-java)",
                  MESHTOPO_LCM_JAR);
        return CLI_EXIT_READ;
    }
    if (!file_readable(MESHTOPO_JCHART2D_JAR)) {
        cli_error("spy", "%s (lcm-spy's charts) not found (Debian: libjchart2d-java)",
                  MESHTOPO_JCHART2D_JAR);
        return CLI_EXIT_READ;
    }
    const char *msgs_jar = msgs_jar_find();
    if (!msgs_jar) return CLI_EXIT_READ;
    /* lcm-spy opens a window: without a display Java dies with a stack trace. */
    const char *display = getenv("DISPLAY"), *wayland = getenv("WAYLAND_DISPLAY");
    if ((!display || !display[0]) && (!wayland || !wayland[0])) {
        cli_error("spy",
                  "no display (DISPLAY is not set): lcm-spy opens a window; run it on a "
                  "desktop, over ssh -X, or under xvfb-run; `meshtopo watch` prints the "
                  "same traffic as text");
        return CLI_EXIT_READ;
    }

    char class_path[3 * SPY_PATH_MAX];
    int n = snprintf(class_path, sizeof class_path, "%s:%s:%s", MESHTOPO_LCM_JAR,
                     MESHTOPO_JCHART2D_JAR, msgs_jar);
    if (n < 0 || (size_t)n >= sizeof class_path) {
        cli_error("spy", "class path too long: %s", msgs_jar);
        return CLI_EXIT_USAGE;
    }
    char url_arg[SPY_PATH_MAX];
    if (url) {
        n = snprintf(url_arg, sizeof url_arg, "--lcm-url=%s", url);
        if (n < 0 || (size_t)n >= sizeof url_arg) {
            cli_error("spy", "--lcm-url: too long");
            return CLI_EXIT_USAGE;
        }
    }
    char *argv[] = {"java",        "-Djava.net.preferIPv4Stack=true",
                    "-cp",         class_path,
                    "lcm.spy.Spy", url ? url_arg : NULL,
                    NULL};
    fflush(stdout);
    fflush(stderr);
    execv(java, argv);
    cli_error("spy", "cannot start %s: %s", java, strerror(errno));
    return CLI_EXIT_READ;
}

const cli_command cli_cmd_spy = {
    .name = "spy",
    .summary = "start lcm-spy with the meshtopo message types, to watch the bus decoded",
    .synopsis = "[--lcm-url URL]",
    .description =
        "Starts lcm-spy (a window; it needs a display) with meshtopo's message types on its\n"
        "class path, so mesh_t, query_t, reply_t, ack_t, topology_t and status_t messages\n"
        "are shown decoded.\n"
        "Runs java -cp lcm.jar:jchart2d.jar:meshtopo-msgs.jar lcm.spy.Spy itself: this\n"
        "process becomes lcm-spy. meshtopo-msgs.jar is $" SPY_ENV_MSGS_JAR
        " when set, else the\n"
        "build tree's, else the installed one (share/java/meshtopo-msgs.jar).\n"
        "\n"
        "exit codes: 2 usage error, 3 java, lcm.jar, jchart2d.jar or meshtopo-msgs.jar is\n"
        "missing (the message names the Debian package) or there is no display;\n"
        "otherwise lcm-spy's own.\n",
    .options = options,
    .num_options = sizeof options / sizeof options[0],
    .min_positionals = 0,
    .max_positionals = 0,
    .run = run_spy,
};
