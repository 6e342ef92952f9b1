/* ex_args.c — see ex_args.h */
#include "ex_args.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

extern char *program_invocation_short_name; /* glibc */

void ex_fail(int status, const char *fmt, ...)
{
    va_list ap;
    fprintf(stderr, "%s: ", program_invocation_short_name);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
    exit(status);
}

static const char *ex__args_kind_meta(ex_flag_kind_t k)
{
    return k == EX_FLAG_INT ? " N" : k == EX_FLAG_DOUBLE ? " X" : k == EX_FLAG_STRING ? " NAME" : "";
}

static void ex__args_list(FILE *f, const char *const *names)
{
    for (; names && *names; names++) fprintf(f, "%s%s", *names, names[1] ? "|" : "");
}

static void ex__args_usage_to(FILE *f, const ex_args_spec_t *spec, const ex_args_t *d)
{
    int i;
    fprintf(f, "usage: %s [flags]\n", program_invocation_short_name);
    if (spec && spec->summary) fprintf(f, "  %s\n", spec->summary);
    fprintf(f, "  --demo DIR      render the gallery image(s) into DIR\n"
                    "  --out FILE      write the image to FILE (.png or .exr)\n");
    fprintf(f, "  --width N       image width in pixels (default %d)\n", d->width);
    fprintf(f, "  --height N      image height in pixels (default %d)\n", d->height);
    fprintf(f, "  --spp N         samples per pixel (default %d)\n", d->spp);
    fprintf(f, "  --threads N     worker threads, 0 = every core (default %d)\n", d->threads);
    if (spec && spec->scenes) {
        fprintf(f, "  --scene NAME    one of ");
        ex__args_list(f, spec->scenes);
        fprintf(f, " (default %s)\n", d->scene ? d->scene : "-");
    }
    if (spec && spec->modes) {
        fprintf(f, "  --mode NAME     one of ");
        ex__args_list(f, spec->modes);
        fprintf(f, " (default %s)\n", d->mode ? d->mode : "-");
    }
    for (i = 0; spec && i < spec->nextra; i++) {
        const ex_flag_t *flag = &spec->extra[i];
        char left[64];
        snprintf(left, sizeof left, "--%s%s", flag->name, ex__args_kind_meta(flag->kind));
        fprintf(f, "  %-15s %s\n", left, flag->help ? flag->help : "");
    }
    fprintf(f, "  --selftest      run the self checks and exit\n"
               "  --help          this text\n");
}

void ex_args_usage(const ex_args_spec_t *spec, const ex_args_t *defaults)
{
    ex__args_usage_to(stderr, spec, defaults);
}

/* Prints one line and the usage, exits 2. */
static void ex__args_bad(const ex_args_spec_t *spec, const ex_args_t *d, const char *fmt, const char *a,
                         const char *b)
{
    fprintf(stderr, "%s: ", program_invocation_short_name);
    fprintf(stderr, fmt, a, b);
    fputc('\n', stderr);
    ex_args_usage(spec, d);
    exit(2);
}

static int ex__args_int(const char *s, long lo, long hi, int *out)
{
    char *end;
    long v;
    errno = 0;
    v = strtol(s, &end, 10);
    if (errno || end == s || *end || v < lo || v > hi) return -1;
    *out = (int)v;
    return 0;
}

static int ex__args_double(const char *s, double *out)
{
    char *end;
    double v;
    errno = 0;
    v = strtod(s, &end);
    if (errno || end == s || *end || v != v || v - v != 0) return -1;
    *out = v;
    return 0;
}

static int ex__args_in(const char *const *names, const char *s)
{
    if (!names) return 1;
    for (; *names; names++)
        if (!strcmp(*names, s)) return 1;
    return 0;
}

/* Flag name without "--" and an inline "=value"; returns the name length. */
static size_t ex__args_split(const char *arg, const char **inline_value)
{
    const char *eq = strchr(arg, '=');
    *inline_value = eq ? eq + 1 : NULL;
    return eq ? (size_t)(eq - arg) : strlen(arg);
}

static const ex_flag_t *ex__args_find_extra(const ex_args_spec_t *spec, const char *name, size_t len)
{
    int i;
    for (i = 0; spec && i < spec->nextra; i++)
        if (strlen(spec->extra[i].name) == len && !strncmp(spec->extra[i].name, name, len)) return &spec->extra[i];
    return NULL;
}

static int ex__args_is(const char *name, size_t len, const char *flag)
{
    return strlen(flag) == len && !strncmp(name, flag, len);
}

static int ex__args_known(const char *name, size_t len)
{
    static const char *const common[] = {"help", "selftest", "demo", "out", "width", "height",
                                         "spp", "threads", "scene", "mode", NULL};
    const char *const *c;
    for (c = common; *c; c++)
        if (ex__args_is(name, len, *c)) return 1;
    return 0;
}

void ex_args_parse(int argc, char **argv, const ex_args_spec_t *spec, ex_args_t *a)
{
    ex_args_t defaults = *a;
    int i;
    for (i = 1; i < argc; i++) {
        const char *arg = argv[i], *name, *val;
        const ex_flag_t *extra;
        size_t len;
        int is_bool;
        if (strncmp(arg, "--", 2) != 0) ex__args_bad(spec, &defaults, "unexpected argument '%s'%s", arg, "");
        name = arg + 2;
        len = ex__args_split(name, &val);
        extra = ex__args_find_extra(spec, name, len);
        if (!extra && !ex__args_known(name, len)) ex__args_bad(spec, &defaults, "unknown flag '%s'%s", arg, "");
        is_bool = ex__args_is(name, len, "help") || ex__args_is(name, len, "selftest") ||
                  (extra && extra->kind == EX_FLAG_BOOL);
        if (is_bool) {
            if (val) ex__args_bad(spec, &defaults, "flag '%s' takes no value%s", arg, "");
        } else if (!val) {
            if (i + 1 >= argc) ex__args_bad(spec, &defaults, "flag '%s' needs a value%s", arg, "");
            val = argv[++i];
        }
        if (ex__args_is(name, len, "help")) { ex__args_usage_to(stdout, spec, &defaults); exit(0); }
        else if (ex__args_is(name, len, "selftest")) a->selftest = 1;
        else if (ex__args_is(name, len, "demo")) a->demo_dir = val;
        else if (ex__args_is(name, len, "out")) a->out = val;
        else if (ex__args_is(name, len, "width")) {
            if (ex__args_int(val, 1, 16384, &a->width)) ex__args_bad(spec, &defaults, "bad --width '%s' (want 1..16384)%s", val, "");
        } else if (ex__args_is(name, len, "height")) {
            if (ex__args_int(val, 1, 16384, &a->height)) ex__args_bad(spec, &defaults, "bad --height '%s' (want 1..16384)%s", val, "");
        } else if (ex__args_is(name, len, "spp")) {
            if (ex__args_int(val, 1, 1000000, &a->spp)) ex__args_bad(spec, &defaults, "bad --spp '%s' (want 1..1000000)%s", val, "");
        } else if (ex__args_is(name, len, "threads")) {
            if (ex__args_int(val, 0, 1024, &a->threads)) ex__args_bad(spec, &defaults, "bad --threads '%s' (want 0..1024)%s", val, "");
        } else if (ex__args_is(name, len, "scene")) {
            if (!ex__args_in(spec ? spec->scenes : NULL, val)) ex__args_bad(spec, &defaults, "unknown --scene '%s'%s", val, "");
            a->scene = val;
        } else if (ex__args_is(name, len, "mode")) {
            if (!ex__args_in(spec ? spec->modes : NULL, val)) ex__args_bad(spec, &defaults, "unknown --mode '%s'%s", val, "");
            a->mode = val;
        } else if (extra) {
            int bad = 0;
            if (extra->kind == EX_FLAG_BOOL) *(int *)extra->value = 1;
            else if (extra->kind == EX_FLAG_INT) bad = ex__args_int(val, INT_MIN, INT_MAX, (int *)extra->value);
            else if (extra->kind == EX_FLAG_DOUBLE) bad = ex__args_double(val, (double *)extra->value);
            else *(const char **)extra->value = val;
            if (bad) ex__args_bad(spec, &defaults, "bad value '%s' for --%s", val, extra->name);
        } else {
            ex__args_bad(spec, &defaults, "unknown flag '%s'%s", arg, "");
        }
        if (val && !*val && !is_bool) ex__args_bad(spec, &defaults, "empty value for '%s'%s", arg, "");
    }
}

/* mkdir -p; returns 0 or -1 with errno set. */
static int ex__args_mkdirs(const char *dir)
{
    char tmp[4096];
    size_t n = strlen(dir), i;
    if (n == 0 || n >= sizeof tmp) { errno = ENAMETOOLONG; return -1; }
    memcpy(tmp, dir, n + 1);
    for (i = 1; i <= n; i++) {
        if (tmp[i] != '/' && tmp[i] != '\0') continue;
        tmp[i] = '\0';
        if (mkdir(tmp, 0777) != 0 && errno != EEXIST) return -1;
        tmp[i] = i < n ? '/' : '\0';
    }
    return 0;
}

/* Fails unless dir is an existing directory (created first when `create`). */
static void ex__args_need_dir(const char *dir, int create)
{
    struct stat st;
    if (create && ex__args_mkdirs(dir) != 0) ex_fail(1, "cannot create directory %s/: %s", dir, strerror(errno));
    if (stat(dir, &st) != 0) ex_fail(1, "cannot write to %s/: %s", dir, strerror(errno));
    if (!S_ISDIR(st.st_mode)) ex_fail(1, "cannot write to %s/: not a directory", dir);
}

/* Fails unless `path` can be opened for writing; a file created by the probe
   is removed again. Catches what access() misses (read-only or pseudo file
   systems, running as root). */
static void ex__args_probe_file(const char *path)
{
    struct stat st;
    int existed = stat(path, &st) == 0, fd;
    if (existed && S_ISDIR(st.st_mode)) ex_fail(1, "cannot write %s: it is a directory", path);
    fd = open(path, O_WRONLY | O_CREAT, 0666);
    if (fd < 0) ex_fail(1, "cannot write %s: %s", path, strerror(errno));
    close(fd);
    if (!existed) unlink(path);
}

/* The directory part of path ("." when none). */
static void ex__args_dirname(const char *path, char *dir, size_t size)
{
    snprintf(dir, size, "%s", path);
    if (strrchr(dir, '/')) {
        *strrchr(dir, '/') = '\0';
        if (!dir[0]) snprintf(dir, size, "/");
    } else snprintf(dir, size, ".");
}

static void ex__args_join(char *buf, size_t size, const char *dir, const char *name)
{
    int n = snprintf(buf, size, "%s/%s", dir, name);
    if (n < 0 || (size_t)n >= size) ex_fail(1, "output path too long: %s/%s", dir, name);
}

const char *ex_args_output_extra(const ex_args_t *a, const char *name, char *buf, size_t size)
{
    char dir[4096];
    if (a->demo_dir) snprintf(dir, sizeof dir, "%s", a->demo_dir);
    else if (a->out) ex__args_dirname(a->out, dir, sizeof dir);
    else snprintf(dir, sizeof dir, ".");
    ex__args_need_dir(dir, a->demo_dir != NULL);
    ex__args_join(buf, size, dir, name);
    ex__args_probe_file(buf);
    return buf;
}

const char *ex_args_output(const ex_args_t *a, const char *name, char *buf, size_t size)
{
    char dir[4096];
    if (!a->out) return ex_args_output_extra(a, name, buf, size);
    if (strlen(a->out) >= size) ex_fail(1, "output path too long: %s", a->out);
    snprintf(buf, size, "%s", a->out);
    ex__args_dirname(a->out, dir, sizeof dir);
    ex__args_need_dir(dir, 0);
    ex__args_probe_file(buf);
    return buf;
}
