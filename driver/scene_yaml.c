/*
 * scene_yaml.c -- the scene loader's view of the raw YAML: a light tree
 * built with libyaml (so every field path has a line), path lookups, the
 * error list, and the translation of libcyaml's log into "FILE:LINE: FIELD:
 * what, expected ..." messages.
 */
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <yaml.h>

#include "scene_internal.h"

/* ---- Tree ---------------------------------------------------------------- */

static cti_ynode *ynode_new(int kind, int line)
{
    cti_ynode *n = calloc(1, sizeof *n);
    if (n) {
        n->kind = kind;
        n->line = line;
    }
    return n;
}

void cti_ynode_free(cti_ynode *n)
{
    if (!n)
        return;
    for (int i = 0; i < n->n; i++) {
        cti_ynode_free(n->child[i]);
        if (n->key)
            free(n->key[i]);
    }
    free(n->child);
    free(n->key);
    free(n->key_line);
    free(n->value);
    free(n);
}

static int ynode_push(cti_ynode *p, char *key, int key_line, cti_ynode *c)
{
    if (p->n == p->cap) {
        int cap = p->cap ? 2 * p->cap : 4;
        cti_ynode **ch = realloc(p->child, (size_t)cap * sizeof *ch);
        if (!ch)
            return -1;
        p->child = ch;
        char **k = realloc(p->key, (size_t)cap * sizeof *k);
        if (!k)
            return -1;
        p->key = k;
        int *kl = realloc(p->key_line, (size_t)cap * sizeof *kl);
        if (!kl)
            return -1;
        p->key_line = kl;
        p->cap = cap;
    }
    p->child[p->n] = c;
    p->key[p->n] = key;
    p->key_line[p->n] = key_line;
    p->n++;
    return 0;
}

/* The deepest nesting of sequences and mappings read. A scene needs four
 * levels (interfaces[0].curve[0][0]); the tree is built recursively, so
 * without a limit a file of a million '[' would overflow the stack. */
#define YAML_MAXDEPTH 64

typedef struct ybuild {
    yaml_parser_t parser;
    char path[512];
    int depth;
    int err_line;
    char err[256];
} ybuild;

static int next_event(ybuild *b, yaml_event_t *ev)
{
    if (!yaml_parser_parse(&b->parser, ev)) {
        const yaml_parser_t *p = &b->parser;
        b->err_line = (int)p->problem_mark.line + 1;
        if (p->context)
            snprintf(b->err, sizeof b->err, "malformed YAML: %s %s", p->problem ? p->problem : "error",
                     p->context);
        else
            snprintf(b->err, sizeof b->err, "malformed YAML: %s", p->problem ? p->problem : "error");
        return -1;
    }
    return 0;
}

/* Build the node whose first event is ev (consumed). */
static cti_ynode *build_node(ybuild *b, yaml_event_t *ev)
{
    int line = (int)ev->start_mark.line + 1;
    if (ev->type == YAML_SCALAR_EVENT) {
        cti_ynode *n = ynode_new(CTI_Y_SCALAR, line);
        if (n)
            n->value = strdup((const char *)ev->data.scalar.value);
        yaml_event_delete(ev);
        return n;
    }
    if (ev->type == YAML_ALIAS_EVENT) {
        cti_ynode *n = ynode_new(CTI_Y_SCALAR, line);
        if (n)
            n->value = strdup("*alias");
        yaml_event_delete(ev);
        return n;
    }
    int seq = ev->type == YAML_SEQUENCE_START_EVENT;
    yaml_event_delete(ev);
    if (b->depth >= YAML_MAXDEPTH) {
        b->err_line = line;
        snprintf(b->err, sizeof b->err,
                 "malformed YAML: lists and mappings nested deeper than %d levels",
                 YAML_MAXDEPTH);
        return NULL;
    }
    cti_ynode *n = ynode_new(seq ? CTI_Y_SEQ : CTI_Y_MAP, line);
    if (!n)
        return NULL;
    b->depth++;
    size_t plen = strlen(b->path);
    for (;;) {
        yaml_event_t e;
        if (next_event(b, &e) != 0)
            goto fail;
        if (e.type == YAML_SEQUENCE_END_EVENT || e.type == YAML_MAPPING_END_EVENT) {
            yaml_event_delete(&e);
            break;
        }
        char *key = NULL;
        int key_line = (int)e.start_mark.line + 1;
        if (seq) {
            snprintf(b->path + plen, sizeof b->path - plen, "[%d]", n->n);
        } else {
            key = strdup(e.type == YAML_SCALAR_EVENT ? (const char *)e.data.scalar.value : "?");
            yaml_event_delete(&e);
            snprintf(b->path + plen, sizeof b->path - plen, "%s%s", plen ? "." : "",
                     key ? key : "?");
            if (next_event(b, &e) != 0) {
                free(key);
                goto fail;
            }
        }
        cti_ynode *c = build_node(b, &e);
        if (!c || ynode_push(n, key, key_line, c) != 0) {
            free(key);
            cti_ynode_free(c);
            goto fail;
        }
        b->path[plen] = '\0';
    }
    b->depth--;
    return n;
fail:
    b->depth--;
    cti_ynode_free(n);
    return NULL;
}

cti_ynode *cti_yaml_read(const char *path, int *line, char *field, size_t fieldlen, char *msg,
                         size_t msglen)
{
    *line = 0;
    field[0] = '\0';
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(msg, msglen, "cannot open the scene file: %s", strerror(errno));
        return NULL;
    }
    struct stat st;
    if (fstat(fileno(f), &st) == 0 && S_ISDIR(st.st_mode)) {
        fclose(f); /* libyaml said "input error" */
        snprintf(msg, msglen, "cannot read the scene file: it is a directory");
        return NULL;
    }
    ybuild b;
    memset(&b, 0, sizeof b);
    if (!yaml_parser_initialize(&b.parser)) {
        fclose(f);
        snprintf(msg, msglen, "cannot initialise libyaml");
        return NULL;
    }
    yaml_parser_set_input_file(&b.parser, f);
    cti_ynode *root = NULL;
    yaml_event_t e;
    int ok = 1;
    /* Stream start, document start, the root node, document end. */
    while (ok) {
        if (next_event(&b, &e) != 0) {
            ok = 0;
            break;
        }
        if (e.type == YAML_STREAM_END_EVENT) {
            yaml_event_delete(&e);
            break;
        }
        if (e.type == YAML_SCALAR_EVENT || e.type == YAML_SEQUENCE_START_EVENT ||
            e.type == YAML_MAPPING_START_EVENT || e.type == YAML_ALIAS_EVENT) {
            if (root) { /* a second document: only the first is read */
                yaml_event_delete(&e);
                break;
            }
            root = build_node(&b, &e);
            if (!root)
                ok = 0;
            continue;
        }
        yaml_event_delete(&e);
    }
    yaml_parser_delete(&b.parser);
    fclose(f);
    if (!ok) {
        cti_ynode_free(root);
        *line = b.err_line;
        snprintf(field, fieldlen, "%s", b.path);
        snprintf(msg, msglen, "%s", b.err[0] ? b.err : "out of memory");
        return NULL;
    }
    if (!root) {
        *line = 1;
        snprintf(msg, msglen, "the file is empty, expected a mapping with end_time, mesh, parts");
        return NULL;
    }
    return root;
}

/* ---- Paths --------------------------------------------------------------- */

/* Walk `path`; *last_line receives the line of the deepest existing step. */
static const cti_ynode *walk(const cti_ynode *root, const char *path, int *last_line, int *complete)
{
    const cti_ynode *n = root;
    *last_line = root ? root->line : 0;
    *complete = 0;
    const char *p = path;
    while (n && *p) {
        if (*p == '.')
            p++;
        if (*p == '[') {
            char *end;
            long i = strtol(p + 1, &end, 10);
            if (*end != ']' || n->kind != CTI_Y_SEQ || i < 0 || i >= n->n)
                return NULL;
            n = n->child[i];
            *last_line = n->line;
            p = end + 1;
        } else {
            size_t len = strcspn(p, ".[");
            if (n->kind != CTI_Y_MAP)
                return NULL;
            int found = -1;
            for (int i = 0; i < n->n; i++)
                if (n->key[i] && strlen(n->key[i]) == len && strncmp(n->key[i], p, len) == 0)
                    found = i;
            if (found < 0)
                return NULL;
            *last_line = n->key_line[found];
            n = n->child[found];
            p += len;
        }
    }
    *complete = 1;
    return n;
}

const cti_ynode *cti_ynode_at(const cti_ynode *root, const char *path)
{
    int line, complete;
    const cti_ynode *n = walk(root, path, &line, &complete);
    return complete ? n : NULL;
}

int cti_path_line(const cti_ynode *root, const char *path)
{
    int line, complete;
    walk(root, path, &line, &complete);
    return line;
}

void cti_quote_value(const char *s, char *buf, size_t len)
{
    size_t n = strlen(s), cut = n > 60 ? 60 : n;
    /* When the first byte left out continues a UTF-8 sequence (10xxxxxx),
     * leave out the whole sequence: back to its lead byte. */
    if (cut < n) {
        size_t k = cut;
        while (k > 0 && ((unsigned char)s[k] & 0xC0) == 0x80)
            k--;
        cut = k;
    }
    snprintf(buf, len, "'%.*s%s'", (int)cut, s, cut < n ? "..." : "");
}

void cti_ynode_describe(const cti_ynode *n, char *buf, size_t len)
{
    if (!n)
        snprintf(buf, len, "nothing");
    else if (n->kind == CTI_Y_SEQ)
        snprintf(buf, len, "a list");
    else if (n->kind == CTI_Y_MAP)
        snprintf(buf, len, "a mapping");
    else if (!n->value[0])
        snprintf(buf, len, "an empty value");
    else
        cti_quote_value(n->value, buf, len);
}

/* ---- Errors -------------------------------------------------------------- */

int cti_err(cti_errs *e, int code, int line, const char *field, const char *fmt, ...)
{
    if (e->count == 0)
        e->code = code;
    int l = e->root && field && field[0] ? cti_path_line(e->root, field) : 0;
    if (l <= 0)
        l = line;
    if (e->out && e->count < CTD_SCENE_MAXERR) {
        ctd_scene_msg *m = &e->out->msg[e->count];
        char what[512];
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(what, sizeof what, fmt, ap);
        va_end(ap);
        m->line = l;
        snprintf(m->field, sizeof m->field, "%s", field ? field : "");
        if (l <= 0)
            snprintf(m->text, sizeof m->text, "%s: %s", e->file, what);
        else if (field && field[0])
            snprintf(m->text, sizeof m->text, "%s:%d: %s: %s", e->file, l, field, what);
        else
            snprintf(m->text, sizeof m->text, "%s:%d: %s", e->file, l, what);
    }
    e->count++;
    if (e->out) {
        e->out->count = e->count;
        e->out->code = e->code;
    }
    return code;
}

/* One backtrace step of libcyaml's log: "  in mapping field 'K' (line: L,
 * column: C)", "  in sequence entry 'N' (line ...)", "  in mapping (...)". */
typedef struct bt_step {
    int kind; /* 0 field, 1 entry, 2 mapping */
    char key[64];
    int index, line;
} bt_step;

static int parse_step(const char *s, bt_step *st)
{
    const char *l = strstr(s, "(line: ");
    st->line = l ? atoi(l + 7) : 0;
    st->key[0] = '\0';
    const char *q = strchr(s, '\'');
    const char *q2 = q ? strchr(q + 1, '\'') : NULL;
    if (strstr(s, "in mapping field") && q && q2) {
        st->kind = 0;
        snprintf(st->key, sizeof st->key, "%.*s", (int)(q2 - q - 1), q + 1);
        return 0;
    }
    if (strstr(s, "in sequence entry") && q) {
        st->kind = 1;
        st->index = atoi(q + 1) - 1; /* libcyaml counts entries from 1 */
        return 0;
    }
    if (strstr(s, "in mapping")) {
        st->kind = 2;
        return 0;
    }
    return -1;
}

void cti_cyaml_error(cti_errs *e, cyaml_err_t rc, const char *log)
{
    /* The first "Load: " line is the message; the steps follow. */
    char first[256] = "";
    bt_step steps[32];
    int ns = 0;
    const char *p = log;
    while (p && *p) {
        const char *nl = strchr(p, '\n');
        size_t len = nl ? (size_t)(nl - p) : strlen(p);
        char line[512];
        snprintf(line, sizeof line, "%.*s", (int)(len < 511 ? len : 511), p);
        if (strncmp(line, "Load: ", 6) == 0 && strncmp(line, "Load: Backtrace", 15) != 0) {
            if (!first[0])
                snprintf(first, sizeof first, "%.250s", line + 6);
        } else if (ns < 32 && parse_step(line, &steps[ns]) == 0) {
            ns++;
        }
        p = nl ? nl + 1 : NULL;
    }
    const char *missing = strstr(first, "Missing required mapping field: ");
    const char *unknown = strstr(first, "Unexpected key: ");
    const char *twice = strstr(first, "Mapping field already seen: ");
    /* For a missing field the innermost step is the last field read of the
     * mapping, not part of the path. */
    int skip = (missing && ns > 0 && steps[0].kind == 0) ? 1 : 0;
    char path[256] = "";
    size_t off = 0;
    for (int i = ns - 1; i >= skip; i--) {
        if (steps[i].kind == 0)
            off += (size_t)snprintf(path + off, sizeof path - off, "%s%s", off ? "." : "",
                                    steps[i].key);
        else if (steps[i].kind == 1)
            off += (size_t)snprintf(path + off, sizeof path - off, "[%d]", steps[i].index);
        if (off >= sizeof path)
            off = sizeof path - 1;
    }
    int line = ns > 0 ? steps[0].line : 0;
    char expect[512], got[96];
    if (missing || unknown) {
        const char *key = missing ? missing + 32 : unknown + 16;
        char parent[256];
        snprintf(parent, sizeof parent, "%s", path);
        off += (size_t)snprintf(path + off, sizeof path - off, "%s%s", off ? "." : "", key);
        if (missing) {
            cti_schema_expect(path, 0, expect, sizeof expect);
            cti_err(e, CT_ERR_ARG, line, path, "required field missing (expected %s)",
                    expect[0] ? expect : "a value");
        } else {
            cti_schema_expect(parent, 1, expect, sizeof expect);
            cti_err(e, CT_ERR_ARG, line, path, "unknown field, expected one of %s",
                    expect[0] ? expect : "the documented keys");
        }
        return;
    }
    if (twice) {
        cti_err(e, CT_ERR_ARG, line, path, "field given twice");
        return;
    }
    cti_schema_expect(path, 0, expect, sizeof expect);
    cti_ynode_describe(e->root ? cti_ynode_at(e->root, path) : NULL, got, sizeof got);
    if (expect[0])
        cti_err(e, CT_ERR_ARG, line, path, "expected %s, got %s", expect, got);
    else
        cti_err(e, CT_ERR_ARG, line, path, "%s (%s)", first[0] ? first : "invalid",
                cyaml_strerror(rc));
}
