//! Links with cortex-m-rt's `link.x`, which includes the workspace's `memory.x` (the firmware
//! crate's build script puts it on the linker's path): on the Cortex-M0, the nRF51 map of QEMU's
//! micro:bit, which `memory.x` switches to when `__nrf51` is defined; otherwise the STM32F4's.

fn main() {
    println!("cargo::rerun-if-changed=build.rs");
    if std::env::var("TARGET").is_ok_and(|t| t.starts_with("thumbv6m")) {
        println!("cargo::rustc-link-arg-bins=--defsym=__nrf51=1");
    }
    println!("cargo::rustc-link-arg-bins=-Tlink.x");
}
