/* fact_hang.c — never ends: the `timeout` around QEMU must stop it (124). */
int main(void);
int main(void)
{
    for (;;)
        __asm__ volatile("nop");
}
