@ The end of every file assembled after asm/shared.s (src/hw/kernels.rs): its macros purged, so
@ the next file can define them again.
    .purgem RECIP_MANTISSA
    .purgem RECIP_NORMALISE
    .purgem RECIP_OF_NORMALISED
    .purgem MUL_2_30
    .purgem DEPTH_LIGHT_ROW
    .purgem PUT_BYTE
    .purgem DUFF_ENTER
