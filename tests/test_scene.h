/*
 * test_scene.h -- what the scene-file tests share (tests/test_scene.c, the
 * scene reader; tests/test_scene_check.c, `contact check` and the run's
 * report): the path of a scene of tests/data/scenes, a scene written by
 * the test, a scene file without its Irem_gap.
 */
#ifndef TEST_SCENE_H
#define TEST_SCENE_H

#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include <criterion/criterion.h>

#include "test_util.h"

/* tests/data/scenes/NAME, found from this file's path. */
static inline void scene_path(char *buf, size_t n, const char *name)
{
    char rel[512];
    snprintf(rel, sizeof rel, "data/scenes/%s", name);
    ctt_tests_path(buf, n, rel);
}

/* Write the scene `text` to /tmp/ct_scene_<pid>_<tag>.yaml, its path in p. */
static inline void write_scene_text(char *p, size_t n, const char *tag, const char *text)
{
    snprintf(p, n, "/tmp/ct_scene_%ld_%s.yaml", (long)getpid(), tag);
    FILE *f = fopen(p, "w");
    cr_assert_not_null(f);
    fputs(text, f);
    fclose(f);
}

/* Write the scene file at src to /tmp/ct_scene_<pid>_<tag>.yaml, its path
 * in p, without its `Irem_gap: 2` fields (each with the comma and blanks
 * before it): the scene as it was before it asked for the neighbour
 * exclusion. */
static inline void write_scene_without_irem(char *p, size_t n, const char *tag, const char *src)
{
    FILE *f = fopen(src, "r");
    cr_assert_not_null(f, "cannot read %s", src);
    static char text[1 << 16];
    size_t len = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[len] = 0;
    const char *key = "Irem_gap: 2";
    for (char *k = strstr(text, key); k; k = strstr(text, key)) {
        char *b = k;
        while (b > text && (b[-1] == ' ' || b[-1] == '\n'))
            b--;
        if (b > text && b[-1] == ',')
            b--;
        memmove(b, k + strlen(key), strlen(k + strlen(key)) + 1);
    }
    cr_assert_null(strstr(text, "Irem_gap:"));
    write_scene_text(p, n, tag, text);
}

#endif
