/* fact_fault.c — executes a permanently undefined instruction: the fault
 * handler must print "FAULT: HardFault ..." and exit with 128 + 3 (UsageFault
 * escalates to HardFault because the board leaves it disabled). */
#include "console.h"

int main(void);
int main(void)
{
    con_str("fact_fault: about to fault");
    con_nl();
    __asm__ volatile("udf #0");
    con_str("fact_fault: still running");
    con_nl();
    return 0;
}
