/*
 * test_errors_import.c -- the Radioss reader's error paths that the decks
 * of test_import_radioss.c do not take (driver/import_radioss*.c), suite
 * "errors_import". Each deck is a few lines written to a directory of the
 * test's own and read with ctd_deck_read; the error must carry its code,
 * name the file and the line ("deck.rad:LINE: ", and diag->index the same
 * line), the field or keyword, and what was expected; the deck holds
 * nothing afterwards. One deck is read through a scene, whose message
 * frames the deck's with the scene's file, line and field.
 *
 *  - ids: an element id 0, a shell id and a brick id defined twice, a
 *    /PART, a /GRSHEL/SHEL and a /SURF id defined twice;
 *  - fields: a negative prop_id of a /PART, a list id that is no number;
 *  - elements: a brick with only three distinct nodes, a brick whose
 *    outer face used by a /SURF has no area (named by face, brick and line).
 */
#include <stdio.h>
#include <string.h>

#include "import_radioss.h"
#include "scene.h"
#include "test_errors.h"

/* Four nodes of a unit square in z = 0 (lines 1-5). */
#define NODES4                                                                                  \
    "/NODE\n"                                                                                   \
    "         1                   0                   0                   0\n"                  \
    "         2                   1                   0                   0\n"                  \
    "         3                   1                   1                   0\n"                  \
    "         4                   0                   1                   0\n"

/* Eight nodes of a unit cube (lines 1-9). */
#define NODES8                                                                                  \
    NODES4                                                                                      \
    "         5                   0                   0                   1\n"                  \
    "         6                   1                   0                   1\n"                  \
    "         7                   1                   1                   1\n"                  \
    "         8                   0                   1                   1\n"

/* Nodes 5-8 on nodes 1-4 (lines 6-9): the top of a brick of no height. */
#define FLAT_TOP                                                                                \
    "         5                   0                   0                   0\n"                  \
    "         6                   1                   0                   0\n"                  \
    "         7                   1                   1                   0\n"                  \
    "         8                   0                   1                   0\n"

/* Write `text` as DIR/deck.rad, read it, and expect `code` with "deck.rad:
 * LINE: " and `w1`, `w2` (when not NULL) in the message. */
static void expect_deck_error(const char *dir, const char *text, int code, int line,
                              const char *w1, const char *w2)
{
    ctt_write_file(dir, "deck.rad", text);
    char path[128];
    snprintf(path, sizeof path, "%s/deck.rad", dir);
    ctd_deck d;
    ct_diag g;
    memset(&g, 0, sizeof g);
    int rc = ctd_deck_read(path, &d, &g);
    cr_expect_eq(rc, code, "expected %s, got %s: %s", ct_strerror(code), ct_strerror(rc), g.msg);
    char tag[32];
    snprintf(tag, sizeof tag, "deck.rad:%d: ", line);
    cr_expect(strstr(g.msg, tag) != NULL, "message \"%s\" lacks \"%s\"", g.msg, tag);
    cr_expect_eq(g.index, line, "diag index %ld, expected line %d: %s", (long)g.index, line,
                 g.msg);
    cr_expect(strstr(g.msg, w1) != NULL, "message \"%s\" lacks \"%s\"", g.msg, w1);
    if (w2)
        cr_expect(strstr(g.msg, w2) != NULL, "message \"%s\" lacks \"%s\"", g.msg, w2);
    cr_expect_null(d.node_id, "the deck holds nodes after a failure");
    cr_expect_eq(d.mesh.nseg, 0);
}

Test(errors_import, ids)
{
    char dir[64];
    ctt_tmpdir(dir, "erri");
    /* An element id of 0 (line 7). */
    expect_deck_error(dir,
                      NODES4 "/SHELL/1\n"
                             "         0         1         2         3         4\n",
                      CT_ERR_ARG, 7, "field 'shell_id' of /SHELL/1: expected a positive integer",
                      "got '0'");
    /* Shell 5 twice (lines 7 and 8). */
    expect_deck_error(dir,
                      NODES4 "/SHELL/1\n"
                             "         5         1         2         3         4\n"
                             "         5         1         2         3         3\n",
                      CT_ERR_ARG, 8,
                      "field 'shell_id' of /SHELL/1: element id 5 is defined twice (first on "
                      "line 7)",
                      NULL);
    /* Brick 3 twice, in two parts (lines 11 and 13). */
    expect_deck_error(dir,
                      NODES8 "/BRICK/1\n"
                             "         3         1         2         3         4         5"
                             "         6         7         8\n"
                             "/BRICK/2\n"
                             "         3         1         2         3         4         5"
                             "         6         7         8\n",
                      CT_ERR_ARG, 13,
                      "field 'brick_id' of /BRICK/2: element id 3 is defined twice (first on "
                      "line 11)",
                      NULL);
    /* /PART/4 twice (lines 6 and 9). */
    expect_deck_error(dir,
                      NODES4 "/PART/4\n"
                             "a part\n"
                             "         1         1\n"
                             "/PART/4\n"
                             "the same part\n"
                             "         1         1\n",
                      CT_ERR_ARG, 9,
                      "keyword /PART/4: part id 4 is defined twice (first on line 6)", NULL);
    /* /GRSHEL/SHEL/2 twice (lines 8 and 11). */
    expect_deck_error(dir,
                      NODES4 "/SHELL/1\n"
                             "         1         1         2         3         4\n"
                             "/GRSHEL/SHEL/2\n"
                             "shells\n"
                             "         1\n"
                             "/GRSHEL/SHEL/2\n"
                             "the same shells\n"
                             "         1\n",
                      CT_ERR_ARG, 11,
                      "keyword /GRSHEL/SHEL/2: id 2 is defined twice (first on line 8)", NULL);
    /* Surface 6 as a part surface and as a shell-group surface (lines 8 and
     * 14). */
    expect_deck_error(dir,
                      NODES4 "/SHELL/1\n"
                             "         1         1         2         3         4\n"
                             "/SURF/PART/6\n"
                             "a surface\n"
                             "         1\n"
                             "/GRSHEL/SHEL/2\n"
                             "shells\n"
                             "         1\n"
                             "/SURF/GRSHEL/6\n"
                             "another surface\n"
                             "         2\n",
                      CT_ERR_ARG, 14,
                      "keyword /SURF/GRSHEL/6: id 6 is already used by /SURF/PART/6 on line 8",
                      NULL);
    ctt_rmtree(dir);
}

Test(errors_import, fields)
{
    char dir[64];
    ctt_tmpdir(dir, "erri");
    /* A /PART whose prop_id is negative (line 8). */
    expect_deck_error(dir,
                      NODES4 "/PART/1\n"
                             "a part\n"
                             "        -1         1\n",
                      CT_ERR_ARG, 8,
                      "field 'prop_id' of /PART/1: expected a non-negative integer, got '-1'",
                      NULL);
    /* The second id of a /GRNOD/NODE list line is a word (line 8). */
    expect_deck_error(dir,
                      NODES4 "/GRNOD/NODE/3\n"
                             "nodes\n"
                             "         1       two\n",
                      CT_ERR_ARG, 8,
                      "field 'node_id' (number 2) of /GRNOD/NODE/3: expected a positive integer, "
                      "got 'two'",
                      NULL);
    ctt_rmtree(dir);
}

Test(errors_import, elements)
{
    char dir[64];
    ctt_tmpdir(dir, "erri");
    /* A brick of three distinct nodes (line 11). */
    expect_deck_error(dir,
                      NODES8 "/BRICK/1\n"
                             "         1         1         2         3         3         1"
                             "         2         3         3\n",
                      CT_ERR_DUPNODE, 11,
                      "/BRICK/1 element 1 has only 3 distinct nodes (at least 4 needed)", NULL);
    /* A brick whose top nodes 5-8 lie on its bottom ones: each side face
     * has no area; the part's outer surface (/SURF/PART) takes them. The
     * first is local face 2 (corners 1 2 6 5) of brick 9 on line 11. */
    expect_deck_error(dir,
                      NODES4 FLAT_TOP "/BRICK/1\n"
                             "         9         1         2         3         4         5"
                             "         6         7         8\n"
                             "/SURF/PART/1\n"
                             "the brick's outer surface\n"
                             "         1\n",
                      CT_ERR_DEGENERATE, 11, "face ", "of /BRICK/1 element 9: ");
    ctt_rmtree(dir);
}

/* Through a scene: the scene's file, line and field, then the deck's. */
Test(errors_import, through_a_scene)
{
    char dir[64];
    ctt_tmpdir(dir, "erri");
    ctt_write_file(dir, "deck.rad",
                   NODES4 "/SHELL/1\n"
                          "         5         1         2         3         4\n"
                          "         5         1         2         3         3\n");
    ctt_write_file(dir, "scene.yaml",
                   "end_time: 1.0e-4\n"
                   "mesh:\n"
                   "  - import: {file: deck.rad}\n"
                   "parts:\n"
                   "  - {id: 1, element: shell, thickness: 0.01, material: {E: 2.1e11, nu: 0.3, "
                   "rho: 7800}}\n");
    ctt_cli r = {0};
    cte_run(&r, dir, "", "check scene.yaml");
    CTE_EXPECT(&r, CTD_EXIT_BADINPUT, "scene.yaml:3: mesh[0].import.file: ",
               "deck.rad:8: field 'shell_id' of /SHELL/1: element id 5 is defined twice");
    cr_expect_str_empty(r.out);
    ctt_cli_free(&r);
    ctt_rmtree(dir);
}
