/*
 * output_csv.c -- the CSV time history, the JSON run summary and the
 * gnuplot plot of the energies.
 */
#include <errno.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "output_internal.h"
#include "provenance.h"

#ifdef _OPENMP
#include <omp.h>
#endif

extern char **environ;

/* ---- CSV ------------------------------------------------------------------- */

static void csv_name(FILE *f, const char *s, int k)
{
    int any = 0;
    for (; s && *s; s++) {
        char c = *s;
        int ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                 c == '_' || c == '-';
        fputc(ok ? c : '_', f);
        any = 1;
    }
    if (!any)
        fprintf(f, "if%d", k);
}

int ctd_output_csv_begin(ctd_output *o, int ninterface, const char *const *names)
{
    if (!o || ninterface < 0 || (ninterface > 0 && !names))
        return CT_ERR_ARG;
    if (!o->csv)
        return CT_OK;
    char *path = cti_out_path(o->dir, "history.csv");
    if (!path)
        return cti_out_nomem(o->err, sizeof o->err);
    if (o->csvf)
        fclose(o->csvf);
    o->csvf = fopen(path, "wb");
    if (!o->csvf) {
        int rc = cti_out_fail(o->err, sizeof o->err, "cannot create CSV file", path, errno);
        free(path);
        return rc;
    }
    o->ninterface = ninterface;
    FILE *f = o->csvf;
    fprintf(f, "cycle,time,dt,kinetic,internal,contact,damping,friction,external_work,"
               "energy_error");
    for (int k = 0; k < ninterface; k++) {
        static const char *const col[3] = {"force", "active", "resorts"};
        for (int c = 0; c < 3; c++) {
            fputc(',', f);
            csv_name(f, names[k], k);
            fprintf(f, "_%s", col[c]);
        }
    }
    int bad = fputc('\n', f) == EOF || fflush(f) != 0;
    int rc = bad ? cti_out_fail(o->err, sizeof o->err, "cannot write CSV file", path,
                                errno ? errno : EIO)
                 : CT_OK;
    free(path);
    return rc;
}

int ctd_output_csv_row(ctd_output *o, const ctd_history_row *r)
{
    if (!o || !r)
        return CT_ERR_ARG;
    if (!o->csv)
        return CT_OK;
    if (!o->csvf) {
        snprintf(o->err, sizeof o->err, "CSV row before ctd_output_csv_begin");
        return CT_ERR_ARG;
    }
    if (o->ninterface > 0 && (!r->if_force || !r->if_active || !r->if_resorts)) {
        snprintf(o->err, sizeof o->err, "CSV row without its per-interface arrays");
        return CT_ERR_ARG;
    }
    FILE *f = o->csvf;
    int bad = fprintf(f, "%lld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g",
                      (long long)r->cycle, r->time, r->dt, r->kinetic, r->internal, r->contact,
                      r->damping, r->friction, r->external_work, r->energy_error) < 0;
    for (int k = 0; k < o->ninterface && !bad; k++)
        bad = fprintf(f, ",%.17g,%lld,%lld", r->if_force[k], (long long)r->if_active[k],
                      (long long)r->if_resorts[k]) < 0;
    /* Flushed every row: the history is complete up to the last step
     * whenever the run stops. */
    bad |= fputc('\n', f) == EOF || fflush(f) != 0;
    if (bad) {
        char path[900];
        snprintf(path, sizeof path, "%.880s/history.csv", o->dir);
        return cti_out_fail(o->err, sizeof o->err, "cannot write CSV file", path,
                            errno ? errno : EIO);
    }
    return CT_OK;
}

/* ---- JSON -------------------------------------------------------------------- */

void ctd_json_string(FILE *f, const char *s)
{
    fputc('"', f);
    for (const unsigned char *p = (const unsigned char *)(s ? s : ""); *p; p++) {
        if (*p == '"' || *p == '\\')
            fprintf(f, "\\%c", *p);
        else if (*p == '\n')
            fputs("\\n", f);
        else if (*p == '\t')
            fputs("\\t", f);
        else if (*p < 0x20)
            fprintf(f, "\\u%04x", *p);
        else
            fputc(*p, f);
    }
    fputc('"', f);
}

/* A JSON number: finite values as %.17g, others as null. */
static void jnum(FILE *f, const char *key, double v, int comma)
{
    fprintf(f, "  \"%s\": ", key);
    if (v == v && v - v == 0)
        fprintf(f, "%.17g", v);
    else
        fputs("null", f);
    fputs(comma ? ",\n" : "\n", f);
}

static void jstr(FILE *f, const char *indent, const char *key, const char *v)
{
    fprintf(f, "%s\"%s\": ", indent, key);
    ctd_json_string(f, v);
    fputs(",\n", f);
}

int ctd_output_summary(ctd_output *o, const ctd_run_summary *s)
{
    if (!o || !s || (s->ninterface > 0 && !s->interfaces))
        return CT_ERR_ARG;
    char *path = cti_out_path(o->dir, "summary.json");
    if (!path)
        return cti_out_nomem(o->err, sizeof o->err);
    FILE *f = fopen(path, "wb");
    if (!f) {
        int rc = cti_out_fail(o->err, sizeof o->err, "cannot create summary file", path, errno);
        free(path);
        return rc;
    }
    char machine[512], host[256] = "", date[64] = "";
    ctd_machine_summary(machine, sizeof machine);
    if (gethostname(host, sizeof host - 1) != 0)
        host[0] = '\0';
    time_t now = time(NULL);
    struct tm tmv;
    if (gmtime_r(&now, &tmv))
        strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", &tmv);
    int threads = s->threads;
#ifdef _OPENMP
    if (threads <= 0)
        threads = omp_get_max_threads();
#endif
    fputs("{\n", f);
    jstr(f, "  ", "scene", s->scene);
    jstr(f, "  ", "title", s->title);
    jstr(f, "  ", "status", s->status ? s->status : "unknown");
    fprintf(f, "  \"exit_code\": %d,\n", s->exit_code);
    jstr(f, "  ", "message", s->message);
    fprintf(f, "  \"threads\": %d,\n", threads);
    fprintf(f, "  \"counts\": {\"cycles\": %lld, \"nodes\": %lld, \"elements\": %lld, "
               "\"segments\": %lld, \"output_steps\": %lld, \"interfaces\": %d},\n",
            (long long)s->cycles, (long long)s->nodes, (long long)s->elements,
            (long long)s->segments, (long long)s->output_steps, s->ninterface);
    jnum(f, "end_time", s->end_time, 1);
    jnum(f, "time_reached", s->time_reached, 1);
    jnum(f, "wall_time", s->wall_time, 1);
    jnum(f, "energy_error", s->energy_error, 1);
    jnum(f, "energy_error_max", s->energy_error_max, 1);
    jnum(f, "energy_error_contact", s->energy_error_contact, 1);
    fputs("  \"timers\": {\n", f);
    const char *tn[6] = {"search", "narrow", "force", "assembly", "elements", "other"};
    const double tv[6] = {s->t_search, s->t_narrow, s->t_force, s->t_assembly, s->t_elements,
                          s->t_other};
    for (int k = 0; k < 6; k++)
        fprintf(f, "    \"%s\": %.9g%s\n", tn[k], tv[k] == tv[k] ? tv[k] : 0.0,
                k < 5 ? "," : "");
    fputs("  },\n  \"interfaces\": [", f);
    for (int k = 0; k < s->ninterface; k++) {
        const ctd_if_summary *i = &s->interfaces[k];
        fputs(k ? ",\n    {" : "\n    {", f);
        fputs("\"name\": ", f);
        ctd_json_string(f, i->name);
        fprintf(f, ", \"type\": %d, \"search\": ", i->type);
        ctd_json_string(f, i->search);
        fprintf(f, ", \"max_active\": %lld, \"resorts\": %lld, \"margin\": %.9g, "
                   "\"max_force\": %.9g, \"memory_bytes\": %lld}",
                (long long)i->max_active, (long long)i->resorts, i->margin,
                i->max_force == i->max_force ? i->max_force : 0.0, (long long)i->memory);
    }
    fputs(s->ninterface ? "\n  ],\n" : "],\n", f);
    fputs("  \"provenance\": {\n", f);
    jstr(f, "    ", "build", ct_build_info());
    jstr(f, "    ", "machine", machine);
    jstr(f, "    ", "host", host);
    fputs("    \"date\": ", f);
    ctd_json_string(f, date);
    fputs("\n  }\n}\n", f);
    int bad = ferror(f);
    int e = errno;
    if (fclose(f) != 0) {
        bad = 1;
        e = errno;
    }
    int rc = bad ? cti_out_fail(o->err, sizeof o->err, "cannot write summary file", path,
                                e ? e : EIO)
                 : CT_OK;
    free(path);
    return rc;
}

/* ---- Plot -------------------------------------------------------------------- */

/* 1 when an executable `name` is on PATH. */
static int on_path(const char *name)
{
    const char *path = getenv("PATH");
    if (!path)
        path = "/usr/bin:/bin";
    while (*path) {
        size_t len = strcspn(path, ":");
        char full[1024];
        snprintf(full, sizeof full, "%.*s/%s", (int)(len < 900 ? len : 900), path, name);
        if (len > 0 && access(full, X_OK) == 0)
            return 1;
        path += len;
        if (*path == ':')
            path++;
    }
    return 0;
}

int ctd_output_plot_energies(const char *dir, char *msg, size_t msglen)
{
    if (!dir)
        return CT_ERR_ARG;
    char *gp = cti_out_path(dir, "energies.gp");
    if (!gp)
        return cti_out_nomem(msg, msglen);
    FILE *f = fopen(gp, "wb");
    if (!f) {
        int rc = cti_out_fail(msg, msglen, "cannot create gnuplot script", gp, errno);
        free(gp);
        return rc;
    }
    /* Paths inside the script are relative to the script's directory:
     * gnuplot runs there. */
    fputs("# Energies of history.csv against time (contact driver).\n"
          "set datafile separator ','\n"
          "set terminal png size 1000,600\n"
          "set output 'energies.png'\n"
          "set key outside right\n"
          "set xlabel 'time [s]'\n"
          "set ylabel 'energy [J]'\n"
          "set grid\n"
          "plot 'history.csv' using 2:4 with lines title 'kinetic', \\\n"
          "     '' using 2:5 with lines title 'internal', \\\n"
          "     '' using 2:6 with lines title 'contact', \\\n"
          "     '' using 2:7 with lines title 'damping', \\\n"
          "     '' using 2:8 with lines title 'friction', \\\n"
          "     '' using 2:9 with lines title 'external work', \\\n"
          "     '' using 2:($4+$5+$6+$7+$8-$9) with lines lw 2 title 'total - W_ext'\n",
          f);
    int bad = ferror(f);
    if (fclose(f) != 0 || bad) {
        int rc = cti_out_fail(msg, msglen, "cannot write gnuplot script", gp, errno ? errno : EIO);
        free(gp);
        return rc;
    }
    free(gp);
    if (!on_path("gnuplot")) {
        if (msg && msglen)
            snprintf(msg, msglen,
                     "gnuplot is not installed (make deps installs gnuplot-nox): no energies.png; "
                     "the script is %s/energies.gp",
                     dir);
        return 1;
    }
    /* gnuplot runs in `dir` through sh -c 'cd "$1" && exec gnuplot energies.gp'
     * (the directory passed as an argument, never spliced into the command). */
    char *const argv[] = {"sh", "-c", "cd \"$1\" && exec gnuplot energies.gp >/dev/null 2>&1",
                          "sh", (char *)dir, NULL};
    pid_t pid;
    int rc = posix_spawnp(&pid, "sh", NULL, NULL, argv, environ);
    if (rc != 0)
        return cti_out_fail(msg, msglen, "cannot run gnuplot in", dir, rc);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR)
            return cti_out_fail(msg, msglen, "cannot wait for gnuplot in", dir, errno);
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        if (msg && msglen)
            snprintf(msg, msglen, "gnuplot failed on %s/energies.gp (exit status %d)", dir,
                     WIFEXITED(status) ? WEXITSTATUS(status) : -1);
        return CT_ERR_ARG;
    }
    if (msg && msglen)
        snprintf(msg, msglen, "%s/energies.png", dir);
    return 0;
}
