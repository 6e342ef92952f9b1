/* ex_args.h — the command line every example shares.

   Common flags: --demo DIR, --out FILE, --width N, --height N, --spp N,
   --threads N, --scene NAME, --mode NAME, --selftest, --help; plus flags an
   example adds with an ex_flag_t table. Values are given as "--flag value"
   or "--flag=value". An unknown flag or a bad value prints one line and the
   usage on stderr and exits with status 2; --help prints the usage on stdout
   and exits 0.

   ex_args_t a = {0};
   a.width = 640; a.height = 400; a.spp = 16;      // the example's defaults
   double radius = 0.05;
   static const char *const modes[] = {"ours", "baseline", NULL};
   ex_flag_t extra[] = {{"radius", EX_FLAG_DOUBLE, &radius, "bevel radius (scene units)"}};
   ex_args_spec_t spec = {0};
   spec.summary = "rounded edges beside the sharp baseline";
   spec.modes = modes; spec.extra = extra; spec.nextra = 1;
   ex_args_parse(argc, argv, &spec, &a);
   char path[4096];
   ex_args_output(&a, "rounded_edges.png", path, sizeof path); // --out, or DIR/name */
#ifndef FILIGREE_EX_ARGS_H
#define FILIGREE_EX_ARGS_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ex_args_t {
    const char *demo_dir;   /* --demo DIR: render the gallery image(s) into DIR; NULL if absent */
    const char *out;        /* --out FILE: the main image's path; NULL if absent */
    int width, height;      /* --width, --height: pixels, 1..16384 */
    int spp;                /* --spp: samples per pixel, 1..1000000 */
    int threads;            /* --threads: 0 = every core, else 1..1024 */
    const char *scene;      /* --scene NAME (checked against spec->scenes when given) */
    const char *mode;       /* --mode NAME (checked against spec->modes when given) */
    int selftest;           /* --selftest: run the example's self checks instead */
} ex_args_t;

typedef enum ex_flag_kind_t { EX_FLAG_INT, EX_FLAG_DOUBLE, EX_FLAG_STRING, EX_FLAG_BOOL } ex_flag_kind_t;

/* An example-specific flag "--name": `value` points to an int, double,
   const char * or int (bool, set to 1 and takes no value) per `kind`. */
typedef struct ex_flag_t {
    const char *name;       /* without the leading "--" */
    ex_flag_kind_t kind;
    void *value;            /* holds the default on entry */
    const char *help;
} ex_flag_t;

typedef struct ex_args_spec_t {
    const char *summary;           /* one line shown at the top of the usage */
    const char *const *scenes;     /* NULL-terminated valid --scene names; NULL → any */
    const char *const *modes;      /* NULL-terminated valid --mode names; NULL → any */
    const ex_flag_t *extra;        /* example-specific flags, may be NULL */
    int nextra;
} ex_args_spec_t;

/* Parses argv into *args (which holds the defaults on entry). Exits 2 on bad
   input, 0 after --help. */
void ex_args_parse(int argc, char **argv, const ex_args_spec_t *spec, ex_args_t *args);

/* Prints the usage of this example on stderr. */
void ex_args_usage(const ex_args_spec_t *spec, const ex_args_t *defaults);

/* The path of an output file: --out when given, else DIR/name where DIR is the
   --demo directory (created if missing), else name in the current directory.
   Probes that the file can be written (a probe file it creates is removed);
   on failure prints one line ("cannot write out/x.png: Permission denied")
   and exits 1, so a render never runs only to fail at the end. Returns buf. */
const char *ex_args_output(const ex_args_t *args, const char *name, char *buf, size_t size);

/* Like ex_args_output but always DIR/name (DIR from --demo, else the
   directory of --out, else "."): for an example's secondary images. */
const char *ex_args_output_extra(const ex_args_t *args, const char *name, char *buf, size_t size);

/* Prints "<program>: <message>" on stderr and exits with `status`. */
void ex_fail(int status, const char *fmt, ...) __attribute__((format(printf, 2, 3), noreturn));

#ifdef __cplusplus
}
#endif
#endif /* FILIGREE_EX_ARGS_H */
