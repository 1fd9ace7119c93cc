/* fact_exit.c — returns 42: QEMU must exit with status 42 (SYS_EXIT_EXTENDED
 * carries main's return value; plain SYS_EXIT could only say 0 or 1). Its
 * text goes to the console, which QEMU prints on its stderr. */
#include "console.h"

int main(void);
int main(void)
{
    con_str("fact_exit: console text");
    con_nl();
    return 42;
}
