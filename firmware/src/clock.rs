//! Time measured in ticks of the core clock: on Arm SysTick's, on RISC-V `mcycle`'s. Under QEMU
//! with `-icount shift=0` every instruction advances the virtual clock by one nanosecond, so
//! ticks count instructions exactly and repeatably (one tick of a 168 MHz core is 1000/168
//! instructions; RISC-V's `mcycle` reads the instructions themselves); on a board they count
//! cycles.

#[cfg(target_arch = "riscv32")]
pub use riscv_clock::Clock;
#[cfg(target_arch = "arm")]
pub use systick::Clock;

/// On RISC-V: the cycle counter, `mcycle`, which needs no timer.
#[cfg(target_arch = "riscv32")]
mod riscv_clock {
    /// Cycles, read from `mcycle`.
    #[derive(Debug)]
    pub struct Clock;

    impl Clock {
        /// Lets the cycle counter run: Hazard3 (the RP2350's) resets with it inhibited.
        #[allow(
            unsafe_code,
            reason = "a write to mcountinhibit, which only stops or starts the counters"
        )]
        pub fn start() -> Self {
            // SAFETY: clearing the inhibit bits of mcycle and minstret affects nothing else.
            unsafe {
                riscv::register::mcountinhibit::clear_cy();
                riscv::register::mcountinhibit::clear_ir();
            }
            Self
        }

        /// Cycles since reset.
        pub fn ticks(&self) -> u64 {
            riscv::register::mcycle::read64()
        }

        /// Runs `work` and returns its result with the cycles it took.
        pub fn measure<R>(&self, work: impl FnOnce() -> R) -> (R, u64) {
            let start = self.ticks();
            let result = work();
            (result, self.ticks() - start)
        }
    }
}

/// On Arm: SysTick, extended to 64 bits by its wraps.
#[cfg(target_arch = "arm")]
mod systick {
    use core::sync::atomic::{AtomicU32, Ordering};
    use cortex_m::peripheral::SYST;
    use cortex_m::peripheral::syst::SystClkSource;
    use cortex_m_rt::exception;

    /// SysTick's counter is 24 bits wide: it counts down from here and wraps.
    const RELOAD: u32 = 0x00FF_FFFF;

    /// How many times the counter wrapped; only the SysTick exception writes it.
    static WRAPS: AtomicU32 = AtomicU32::new(0);

    #[exception]
    fn SysTick() {
        WRAPS.store(
            WRAPS.load(Ordering::Relaxed).wrapping_add(1),
            Ordering::Relaxed,
        );
    }

    /// A free-running 64-bit tick counter on SysTick, which it owns.
    pub struct Clock {
        _syst: SYST,
    }

    impl core::fmt::Debug for Clock {
        fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
            f.debug_struct("Clock").finish_non_exhaustive()
        }
    }

    impl Clock {
        /// Starts SysTick on the core clock, wrapping every 2²⁴ ticks into an exception that
        /// extends the count.
        pub fn start(mut syst: SYST) -> Self {
            syst.set_clock_source(SystClkSource::Core);
            syst.set_reload(RELOAD);
            syst.clear_current();
            syst.enable_interrupt();
            syst.enable_counter();
            // The cleared counter reads 0 until its first reload, which would look like a whole
            // period gone by and then time running backwards.
            while SYST::get_current() == 0 {}
            Self { _syst: syst }
        }

        /// Ticks since `start`.
        pub fn ticks(&self) -> u64 {
            loop {
                let wraps = WRAPS.load(Ordering::Relaxed);
                let current = SYST::get_current();
                // A wrap between the two reads would pair the new count with the old wrap count.
                if WRAPS.load(Ordering::Relaxed) == wraps {
                    return u64::from(wraps) * (u64::from(RELOAD) + 1)
                        + u64::from(RELOAD - current);
                }
            }
        }

        /// Runs `work` and returns its result with the ticks it took.
        pub fn measure<R>(&self, work: impl FnOnce() -> R) -> (R, u64) {
            let start = self.ticks();
            let result = work();
            (result, self.ticks() - start)
        }
    }
}
