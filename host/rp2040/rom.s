@ A stand-in for the RP2040's boot ROM, for rp2040js (run.mjs): the table lookup and the
@ functions rp2040-hal takes from the ROM for integer code (bit counts, memset, memcpy). No
@ flash and no USB boot; no floating point: every entry of the float and double tables is
@ `missing` at 0x200, a loop the harness stops at and names.
@ Assemble (host/check.sh checks rom.bin against it): llvm-mc -triple=thumbv6m-none-eabi
@ -filetype=obj rom.s -o rom.o && llvm-objcopy -O binary -j .text rom.o rom.bin
    .syntax unified
    .thumb
    .text
    .org 0
rom:
    .word 0x20042000          @ initial stack pointer (unused: the harness starts in flash)
    .word 0                   @ reset (unused)
    .word 0, 0
    .org 0x10
    .byte 0x4d, 0x75, 0x01, 0x02   @ 'M' 'u' 0x01, version 2 (B2)
    .hword functions - rom          @ 0x14: the function table
    .hword data - rom               @ 0x16: the data table
    .hword lookup - rom             @ 0x18: rom_table_lookup (Thumb)
    .hword 0

    .balign 4
functions:
    .ascii "P3"
    .hword popcount32 - rom
    .ascii "R3"
    .hword reverse32 - rom
    .ascii "L3"
    .hword clz32 - rom
    .ascii "T3"
    .hword ctz32 - rom
    .ascii "MS"
    .hword memset - rom
    .ascii "S4"
    .hword memset4 - rom
    .ascii "MC"
    .hword memcpy - rom
    .ascii "C4"
    .hword memcpy44 - rom
data:
    .ascii "SF"
    .hword floats - rom
    .ascii "SD"
    .hword floats - rom
    .hword 0, 0

@ rom_table_lookup(table: *const u16, code: u32) -> *const ()
    .thumb_func
lookup:
1:  ldrh r2, [r0]
    cmp r2, #0
    beq 2f
    ldrh r3, [r0, #2]
    adds r0, #4
    cmp r2, r1
    bne 1b
    movs r0, r3
    bx lr
2:  movs r0, #0
    bx lr

@ popcount32(x) -> u32
    .thumb_func
popcount32:
    movs r1, #0
1:  cmp r0, #0
    beq 2f
    subs r2, r0, #1
    ands r0, r2
    adds r1, #1
    b 1b
2:  movs r0, r1
    bx lr

@ reverse32(x) -> u32: the bits reversed
    .thumb_func
reverse32:
    movs r1, #0
    movs r2, #32
1:  lsrs r0, r0, #1
    adcs r1, r1
    subs r2, #1
    bne 1b
    movs r0, r1
    bx lr

@ clz32(x) -> u32: leading zeros, 32 for 0
    .thumb_func
clz32:
    movs r1, #32
    cmp r0, #0
    beq 2f
    movs r1, #0
1:  lsls r0, r0, #1
    bcs 2f
    adds r1, #1
    b 1b
2:  movs r0, r1
    bx lr

@ ctz32(x) -> u32: trailing zeros, 32 for 0
    .thumb_func
ctz32:
    movs r1, #32
    cmp r0, #0
    beq 2f
    movs r1, #0
1:  lsrs r0, r0, #1
    bcs 2f
    adds r1, #1
    b 1b
2:  movs r0, r1
    bx lr

@ memset(ptr, c, n) -> ptr
    .thumb_func
memset:
    mov r12, r0
    cmp r2, #0
    beq 2f
1:  strb r1, [r0]
    adds r0, #1
    subs r2, #1
    bne 1b
2:  mov r0, r12
    bx lr

@ memset4(ptr: *mut u32, c, n) -> ptr: n a multiple of 4
    .thumb_func
memset4:
    mov r12, r0
    lsls r3, r1, #24
    lsrs r3, r3, #24
    lsls r1, r3, #8
    orrs r3, r1
    lsls r1, r3, #16
    orrs r3, r1
1:  subs r2, #4
    bmi 2f
    stm r0!, {r3}
    b 1b
2:  mov r0, r12
    bx lr

@ memcpy(dest, src, n) -> dest
    .thumb_func
memcpy:
    mov r12, r0
    cmp r2, #0
    beq 2f
1:  ldrb r3, [r1]
    strb r3, [r0]
    adds r1, #1
    adds r0, #1
    subs r2, #1
    bne 1b
2:  mov r0, r12
    bx lr

@ memcpy44(dest: *mut u32, src: *const u32, n) -> dest: n a multiple of 4
    .thumb_func
memcpy44:
    mov r12, r0
1:  subs r2, #4
    bmi 2f
    ldm r1!, {r3}
    stm r0!, {r3}
    b 1b
2:  mov r0, r12
    bx lr

@ What an image that calls the ROM's floating point reaches: a loop at a fixed address.
    .org 0x200
    .thumb_func
missing:
    b missing

@ The float and double tables: every routine is `missing`.
    .balign 4
floats:
    .rept 64
    .word missing - rom
    .endr
