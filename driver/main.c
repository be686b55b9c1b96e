/* main.c -- placeholder entry point of the contact driver. */
#include <stdio.h>

#include "provenance.h"

int main(void)
{
    ctd_print_provenance(stdout, "# ");
    return 0;
}
