// Runs a Raspberry Pi Pico image in rp2040js and decodes what its SPI sends an ST7789, as the
// panel would: `node run.mjs IMAGE.elf OUT_DIR PIXEL_WRITES TIMEOUT_SECONDS [CORE1]`.
//
// The image is loaded as a board's flash holds it (its ELF's loadable segments), with
// `rom.bin`, obscura's stand-in for the RP2040's boot ROM (rom.s), and started at its vector
// table after the second-stage boot loader, which configures a flash interface rp2040js does
// not emulate. The ST7789 is on SPI1 with its data/command line on GP8 and chip select on GP9
// (the Waveshare Pico-LCD-1.3's wiring, `boards/pico`); each byte takes the 8 clocks of the SPI
// clock the firmware set. Once PIXEL_WRITES pixels have been written (a frame, in its row
// order), the panel's first 240×240 pixels go to OUT_DIR/panel.raw (RGB565, little-endian
// 16-bit words) and a report of what was sent to standard output as JSON.
//
// rp2040js emulates no core 1. CORE1 says what the image finds of it in the SIO's mailboxes:
// `absent` (the default), a status that reads all ones, as rp2040js reads them; `silent`,
// mailboxes that take words and never answer, as from a core 1 that faulted.
import { Simulator } from 'rp2040js';
import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';

const [elfPath, outDir, writesArg, timeoutArg, core1 = 'absent'] = process.argv.slice(2);
if (!elfPath || !outDir || !writesArg || !['absent', 'silent'].includes(core1)) {
  console.error('usage: node run.mjs IMAGE.elf OUT_DIR PIXEL_WRITES [TIMEOUT_SECONDS [absent|silent]]');
  process.exit(2);
}
const wanted = Number(writesArg);
const timeoutMs = 1000 * Number(timeoutArg ?? 600);

const FLASH = 0x10000000;
// rom.s: where its missing routines loop, and how far its code may reach.
const ROM_MISSING = 0x200;
const ROM_BYTES = 0x400;
const BOOT2_BYTES = 0x100;
const SIDE = 240;
const PANEL_ROWS = 320;
const DATA_COMMAND_PIN = 8;
const CHIP_SELECT_PIN = 9;

const simulator = new Simulator();
const { clock } = simulator;
const mcu = simulator.rp2040;
const warnings = [];
mcu.logger = {
  debug() {},
  info() {},
  warn: (component, message) => warnings.length < 10 && warnings.push(`${component}: ${message}`),
  error: (component, message) => warnings.length < 10 && warnings.push(`${component}: ${message}`),
};

// Core 1's mailboxes (SIO FIFO_ST, FIFO_WR, FIFO_RD).
const [FIFO_ST, FIFO_WR, FIFO_RD] = [0x50, 0x54, 0x58];
const FIFO_ROOM = 0x2;
const sioRead = mcu.sio.readUint32.bind(mcu.sio);
const sioWrite = mcu.sio.writeUint32.bind(mcu.sio);
mcu.sio.readUint32 = (offset) => {
  if (offset === FIFO_ST) return core1 === 'silent' ? FIFO_ROOM : 0xffffffff;
  if (offset === FIFO_RD) return core1 === 'silent' ? 0 : 0xffffffff;
  return sioRead(offset);
};
mcu.sio.writeUint32 = (offset, value) => {
  if (offset !== FIFO_WR) sioWrite(offset, value);
};

// The ROM first: loading it resets the chip, which erases the flash.
const rom = readFileSync(new URL('./rom.bin', import.meta.url));
const romWords = new Uint32Array(Math.ceil(rom.length / 4));
new Uint8Array(romWords.buffer).set(rom);
mcu.loadBootrom(romWords);

// The ELF's loadable segments at their physical addresses in flash.
const elf = readFileSync(elfPath);
const word = (at) => elf.readUInt32LE(at);
const half = (at) => elf.readUInt16LE(at);
if (word(0) !== 0x464c457f || elf[4] !== 1 || elf[5] !== 1 || half(18) !== 40) {
  console.error(`${elfPath} is not a 32-bit little-endian Arm ELF image`);
  process.exit(1);
}
for (let i = 0; i < half(44); i++) {
  const header = word(28) + i * half(42);
  const [type, offset, physical, size] = [0, 4, 12, 16].map((at) => word(header + at));
  if (type === 1 && size > 0 && physical >= FLASH && physical + size <= FLASH + mcu.flash.length) {
    mcu.flash.set(elf.subarray(offset, offset + size), physical - FLASH);
  }
}
mcu.core.VTOR = FLASH + BOOT2_BYTES;
mcu.core.SP = mcu.flashView.getUint32(BOOT2_BYTES, true);
mcu.core.PC = (mcu.flashView.getUint32(BOOT2_BYTES + 4, true) & ~1) >>> 0;

// The panel: its memory, its address window and what the commands set.
const panel = new Uint16Array(SIDE * PANEL_ROWS);
const set = { colmod: null, madctl: null, inverted: false, sleeping: true, on: false, resets: 0 };
const window = { x0: 0, x1: SIDE - 1, y0: 0, y1: PANEL_ROWS - 1 };
let command = -1;
let args = [];
let at = { x: 0, y: 0 };
let high = -1;
let bytes = 0;
let writes = 0;
let cycles = 0;
let firstPixel = null;
let lastPixel = null;
let snapshot = null;
const unknown = new Set();
const windows = [];

function onCommand(code) {
  command = code;
  args = [];
  high = -1;
  switch (code) {
    case 0x01: set.resets++; break; // SWRESET
    case 0x11: set.sleeping = false; break; // SLPOUT
    case 0x20: set.inverted = false; break; // INVOFF
    case 0x21: set.inverted = true; break; // INVON
    case 0x29: set.on = true; break; // DISPON
    case 0x2c: at = { x: window.x0, y: window.y0 }; break; // RAMWR
    case 0x13: case 0x2a: case 0x2b: case 0x36: case 0x3a: break;
    default: unknown.add(code);
  }
}

function onData(value) {
  if (command === 0x2c) {
    if (high < 0) {
      high = value;
      return;
    }
    if (at.x < SIDE && at.y < PANEL_ROWS) panel[at.y * SIDE + at.x] = (high << 8) | value;
    high = -1;
    writes++;
    if (writes === 1) firstPixel = { cycles, nanos: clock.nanos };
    if (writes === wanted) {
      lastPixel = { cycles, nanos: clock.nanos };
      snapshot = panel.slice(0, SIDE * SIDE);
    }
    if (++at.x > window.x1) {
      at.x = window.x0;
      if (++at.y > window.y1) at.y = window.y0;
    }
    return;
  }
  args.push(value);
  if ((command === 0x2a || command === 0x2b) && args.length === 4) {
    const [from, to] = [(args[0] << 8) | args[1], (args[2] << 8) | args[3]];
    if (command === 0x2a) [window.x0, window.x1] = [from, to];
    else [window.y0, window.y1] = [from, to];
    if (windows.length < 4 && command === 0x2b) windows.push({ ...window });
  }
  if (command === 0x3a && args.length === 1) set.colmod = value;
  if (command === 0x36 && args.length === 1) set.madctl = value;
}

const spi = mcu.spi[1];
spi.onTransmit = (value) => {
  bytes++;
  if (!mcu.gpio[CHIP_SELECT_PIN].outputValue) {
    if (mcu.gpio[DATA_COMMAND_PIN].outputValue) onData(value);
    else onCommand(value);
  }
  const alarm = clock.createAlarm(() => spi.completeTransmit(0));
  alarm.schedule(8e9 / spi.clockFrequency);
};

const start = Date.now();
let outcome = 'drawn';
for (let step = 0; ; step++) {
  if ((step & 0xfffff) === 0 && Date.now() - start > timeoutMs) {
    outcome = 'timeout';
    break;
  }
  if (mcu.core.waiting) {
    if (snapshot) break;
    const next = clock.nanosToNextAlarm;
    if (!Number.isFinite(next) || next <= 0) {
      outcome = 'asleep';
      break;
    }
    clock.tick(next);
    continue;
  }
  const pc = mcu.core.PC;
  if (pc === ROM_MISSING) {
    outcome =
      "the image calls the boot ROM's floating point, which obscura's stand-in (rom.s) lacks: " +
      'emulate a fixed-point format';
    break;
  }
  if (pc >= ROM_BYTES && pc < FLASH) {
    outcome = `jumped to 0x${pc.toString(16)}, past obscura's stand-in for the boot ROM (rom.s)`;
    break;
  }
  const spent = mcu.core.executeInstruction();
  cycles += spent;
  clock.tick((spent * 1e9) / mcu.clkSys);
  if (snapshot && !mcu.core.waiting && clock.nanos - lastPixel.nanos > 5e8) break;
}

if (snapshot) writeFileSync(join(outDir, 'panel.raw'), Buffer.from(snapshot.buffer));
const report = {
  outcome: snapshot ? 'drawn' : outcome,
  pixel_writes: writes,
  frame_cycles: snapshot ? lastPixel.cycles - firstPixel.cycles : null,
  frame_seconds: snapshot ? (lastPixel.nanos - firstPixel.nanos) / 1e9 : null,
  core_hz: mcu.clkSys,
  spi_hz: spi.clockFrequency,
  bytes,
  colmod: set.colmod,
  madctl: set.madctl,
  inverted: set.inverted,
  sleeping: set.sleeping,
  on: set.on,
  first_windows: windows,
  unknown_commands: [...unknown],
  warnings,
  core1,
  wall_seconds: (Date.now() - start) / 1000,
};
console.log(JSON.stringify(report));
process.exit(snapshot ? 0 : 1);
