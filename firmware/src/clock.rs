//! Time measured in ticks: on Arm, SysTick's of the core clock — under QEMU with `-icount
//! shift=0` every instruction advances the virtual clock by one nanosecond, so ticks count
//! instructions exactly and repeatably (one tick of a 168 MHz core is 1000/168 instructions) —;
//! on RISC-V, the instructions retired themselves (`minstret`).

#[cfg(target_arch = "riscv32")]
pub use riscv_clock::Clock;
#[cfg(target_arch = "arm")]
pub use systick::Clock;

/// On RISC-V: the instructions retired (`minstret`), which need no timer.
#[cfg(target_arch = "riscv32")]
mod riscv_clock {
    /// Instructions retired, read from `minstret`.
    #[derive(Debug)]
    pub struct Clock;

    impl Clock {
        /// The counter runs from reset.
        pub fn start() -> Self {
            Self
        }

        /// Instructions retired since reset.
        pub fn ticks(&self) -> u64 {
            riscv::register::minstret::read64()
        }

        /// Runs `work` and returns its result with the instructions it took.
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
