#include <stdio.h>

#include "cmd.h"

int cmd_info(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    fprintf(stderr, "grano info: the H5MD reader is not built yet\n");
    return 1;
}
