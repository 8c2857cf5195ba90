#!/bin/sh
# Stands in for arm-none-eabi-nm on a pico-sdk image for the heap check: the
# "image" argument is the address of `end` (the end of the static RAM); the
# heap's limit is the RP2040's, 0x20040000.
printf '20040000 B __HeapLimit\n%s B end\n20042000 B __StackTop\n' "$1"
