/*
 * test_scene.h -- what the scene-file tests share (tests/test_scene.c, the
 * scene reader; tests/test_scene_check.c, `contact check` and the run's
 * report): the path of a scene of tests/data/scenes and a scene written by
 * the test.
 */
#ifndef TEST_SCENE_H
#define TEST_SCENE_H

#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include <criterion/criterion.h>

/* tests/data/scenes/NAME, found from this file's path. */
static inline void scene_path(char *buf, size_t n, const char *name)
{
    const char *f = __FILE__, *slash = strrchr(f, '/');
    if (slash)
        snprintf(buf, n, "%.*s/data/scenes/%s", (int)(slash - f), f, name);
    else
        snprintf(buf, n, "data/scenes/%s", name);
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

#endif
