//! Links with cortex-m-rt's `link.x`, which includes the workspace's `memory.x` (the firmware
//! crate's build script puts it on the linker's path): on the Cortex-M0, the nRF51 map of QEMU's
//! micro:bit, which `memory.x` switches to when `__nrf51` is defined; on the Cortex-M33, the
//! AN505 map of QEMU's mps2-an505 (`__an505`); otherwise the STM32F4's.

fn main() {
    println!("cargo::rerun-if-changed=build.rs");
    let target = std::env::var("TARGET").unwrap_or_default();
    if target.starts_with("thumbv6m") {
        println!("cargo::rustc-link-arg-bins=--defsym=__nrf51=1");
    }
    if target.starts_with("thumbv8m") {
        println!("cargo::rustc-link-arg-bins=--defsym=__an505=1");
    }
    if target.starts_with("riscv32") {
        let here = std::env::var("CARGO_MANIFEST_DIR").unwrap_or_default();
        println!("cargo::rustc-link-search={here}");
        println!("cargo::rustc-link-arg-bins=-Tmemory-riscv.x");
    }
    println!("cargo::rustc-link-arg-bins=-Tlink.x");
}
