//! The Raspberry Pi Pico's own image run in an emulator of its chip: `host/rp2040/run.mjs`
//! loads it into rp2040js (Node, pinned by `host/rp2040/package-lock.json`), with obscura's
//! stand-in for the boot ROM, and decodes what the firmware sends the ST7789 as the panel would.
//! This module installs the emulator where it is missing, runs it and reads what it found.

use anyhow::{Context, Result, bail};
use serde::Deserialize;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// What the emulated board's core 1 does: rp2040js emulates no core 1, and its mailboxes to core
/// 1 (the SIO's FIFOs) read as unmapped.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum Core1 {
    /// Missing, as rp2040js has it: the mailboxes' status reads all ones.
    #[default]
    Absent,
    /// Mailboxes that work, to a core 1 that never answers (one that faulted).
    Silent,
}

impl Core1 {
    /// Its name, as `--core1` and `run.mjs` take it.
    pub fn name(self) -> &'static str {
        match self {
            Self::Absent => "absent",
            Self::Silent => "silent",
        }
    }
}

/// What the panel received in a run: its picture and what the commands set.
#[derive(Debug, Deserialize)]
pub struct Run {
    /// How the run ended: `drawn` once the frame's pixels were written.
    pub outcome: String,
    /// Pixels written to the panel's memory, the frame's and what follows (its captions).
    pub pixel_writes: u64,
    /// Core cycles from the frame's first pixel to its last, as rp2040js counts them.
    pub frame_cycles: Option<u64>,
    /// The same in seconds at the clock the firmware set.
    pub frame_seconds: Option<f64>,
    /// The system clock the firmware set.
    pub core_hz: f64,
    /// The SPI clock the firmware set, from the SSP's prescaler and divider.
    pub spi_hz: f64,
    /// Bytes sent on the SPI.
    pub bytes: u64,
    /// The pixel format COLMOD set (0x55: 16 bits a pixel).
    pub colmod: Option<u8>,
    /// The orientation MADCTL set.
    pub madctl: Option<u8>,
    /// Whether the colours are inverted (INVON).
    pub inverted: bool,
    /// Whether the panel was left asleep (no SLPOUT).
    pub sleeping: bool,
    /// Whether the display was switched on (DISPON).
    pub on: bool,
    /// The first address windows CASET and RASET set.
    pub first_windows: Vec<Window>,
    /// Commands the decoder does not know.
    pub unknown_commands: Vec<u8>,
    /// What rp2040js warned of.
    pub warnings: Vec<String>,
    /// Seconds the emulation took.
    pub wall_seconds: f64,
    /// The panel's 240×240 pixels once the frame was written (RGB565).
    #[serde(skip)]
    pub panel: Vec<u16>,
}

/// An address window: columns and rows, inclusive.
#[derive(Debug, Deserialize)]
pub struct Window {
    pub x0: u16,
    pub x1: u16,
    pub y0: u16,
    pub y1: u16,
}

/// The emulator's directory.
fn dir() -> PathBuf {
    crate::firmware::workspace().join("host/rp2040")
}

/// Checks that Node is installed and installs the emulator's pinned packages where they are
/// missing (`npm ci`).
///
/// # Errors
/// Where Node or npm is missing, or the install fails.
pub fn prepare() -> Result<()> {
    let node = Command::new("node")
        .arg("--version")
        .stdout(Stdio::null())
        .status();
    if !node.is_ok_and(|status| status.success()) {
        bail!(
            "Node.js is not installed, which runs the RP2040 emulator; install Node 18 or later \
             (sudo apt-get install nodejs npm, or https://nodejs.org)"
        );
    }
    if dir().join("node_modules/rp2040js").is_dir() {
        return Ok(());
    }
    let status = Command::new("npm")
        .args(["ci", "--no-audit", "--no-fund"])
        .current_dir(dir())
        .status()
        .context("cannot run npm, which installs the RP2040 emulator (it comes with Node.js)")?;
    if !status.success() {
        bail!(
            "npm ci in {} failed (see its messages above)",
            dir().display()
        );
    }
    Ok(())
}

/// Runs the Pico image `elf` until `pixel_writes` pixels reach the panel (a frame in its row
/// order), at most `timeout` seconds, its core 1 as `core1` says, writing the panel's picture
/// into `out`.
///
/// # Errors
/// Where the emulator cannot run, or the frame never reaches the panel.
pub fn run(elf: &Path, out: &Path, pixel_writes: u64, timeout: u64, core1: Core1) -> Result<Run> {
    let output = Command::new("node")
        .arg(dir().join("run.mjs"))
        .arg(elf)
        .arg(out)
        .arg(pixel_writes.to_string())
        .arg(timeout.to_string())
        .arg(core1.name())
        .stderr(Stdio::inherit())
        .output()
        .context("cannot run node")?;
    let text = String::from_utf8_lossy(&output.stdout);
    let mut run: Run = serde_json::from_str(text.trim())
        .with_context(|| format!("the emulator's report is not what run.mjs writes: {text}"))?;
    if !output.status.success() || run.outcome != "drawn" {
        bail!(
            "the frame did not reach the panel in the emulator: {} after {} pixels",
            run.outcome,
            run.pixel_writes
        );
    }
    let raw = std::fs::read(out.join("panel.raw"))
        .with_context(|| format!("cannot read {}", out.join("panel.raw").display()))?;
    run.panel = raw
        .chunks_exact(2)
        .map(|pair| u16::from_le_bytes([pair[0], pair[1]]))
        .collect();
    Ok(run)
}
