//! `obscura preview`: the firmware's render loop on the desktop. The same core draws the scene
//! at the display's size in RGB565, in the firmware's row order and dither, into an
//! embedded-graphics-simulator window, each row appearing when it would on the target's board
//! (paced by [`estimate::frame`]: the Black Pill for the M4F, the Pico for the M0); the final
//! frame, the firmware's to the bit, is written as a PNG. With `--headless` there is no window
//! and no pace. A scene with a camera path plays its frames in a loop, each for the board's
//! estimated frame time, and they are written as a GIF ([`preview_path`]).

use crate::cli::PreviewArgs;
use crate::cost::Machine;
use crate::estimate;
use crate::output::say;
use crate::render::{Request, prepare, rgb565_image};
use anyhow::{Context, Result};
use obscura::methods::MethodName;
use obscura_scene::firmware::SIDE;
use obscura_scene::{Animation, FormatChoice, NamedScene};
use rayon::prelude::*;
use std::time::Duration;

pub fn run(args: &PreviewArgs) -> Result<()> {
    crate::output::check_file(&args.output)?;
    super::on_scene(&args.scene, &args.frame.sampling, |named| {
        preview(args, named)
    })
}

fn preview(args: &PreviewArgs, named: &NamedScene) -> Result<()> {
    if let Some(animation) = &named.scene.animation {
        return preview_path(args, named, animation);
    }
    let methods = args.frame.methods.methods();
    let machine = Machine::from(args.target);
    let (format, scene) = super::board_scene(&args.frame, named, machine)?;
    if let FormatChoice::Given(format) = args.frame.format {
        super::refuse_useless_unseen(&args.refusal, format, &named.scene, methods, (SIDE, SIDE))?;
    }
    let request = Request::new(scene.desc(), (SIDE, SIDE), methods);
    let prepared = prepare(format, &request)?;
    let presentation = args.frame.presentation.presentation();
    // An estimate that cannot be made (its pricing scene's files gone from an installed
    // harness's workspace) leaves the frame unpaced, not undrawn.
    let estimate = estimate::frame(args.target, format, &request.desc, methods);
    say!(
        "{} in {} on the {}, rows {}, dither {}: {}",
        named.name,
        crate::analysis::with_pixels(format, scene.pixels),
        args.target.board().name,
        presentation.order.name(),
        presentation.dither.name(),
        match &estimate {
            Ok(Some(e)) => format!(
                "about {} ({:.0} instructions, {:.0} cycles a pixel, {} core{} at {} MHz), \
                 estimated by the instructions and cycles an operation takes in `{}` in {} under \
                 QEMU (`obscura firmware` measures it)",
                e.board.describe(e.time(presentation.order)),
                e.per_pixel.instructions,
                e.per_pixel.cycles,
                e.board.cores,
                if e.board.cores == 1 { "" } else { "s" },
                e.board.core_hz / 1_000_000,
                e.priced_by,
                e.priced_in,
            ),
            Ok(None) => "no firmware runs this format, nothing to pace it by".to_owned(),
            Err(error) => format!("drawn unpaced, no estimate: {error:#}"),
        }
    )?;
    let frame_time = estimate
        .ok()
        .flatten()
        .map(|e| Duration::from_secs_f64(e.time(presentation.order).frame));
    let pixels = if args.headless {
        prepared.rgb565_frame(presentation, &mut |_, _| {})?
    } else {
        window::show(&named.name, prepared.as_ref(), presentation, frame_time)?
    };
    super::save(&rgb565_image(&pixels, SIDE), &args.output)?;
    say!("wrote {}", args.output.display())?;
    Ok(())
}

/// A camera path as the board shows it: every frame drawn in the format the board takes for the
/// worst, in RGB565, its row order and dither; in the window, frame after frame at the board's
/// estimated pace, looping until the window closes; the frames written as a GIF at the same
/// pace (at the path's own where a frame has no estimate), to `--output` with the extension
/// `.gif`.
fn preview_path(args: &PreviewArgs, named: &NamedScene, animation: &Animation) -> Result<()> {
    let methods = args.frame.methods.methods();
    let frames = named.frames();
    let machine = Machine::from(args.target);
    let (format, found) = super::firmware_format(
        args.frame.format,
        &frames,
        methods,
        (machine, args.frame.target_psnr),
        super::chooses_pixels(&args.frame.sampling, frames.iter().map(|f| &f.scene)),
    )?;
    let presentation = args.frame.presentation.presentation();
    let draw = |frame: &NamedScene| -> Result<(Vec<u16>, Option<Duration>)> {
        if let FormatChoice::Given(format) = args.frame.format {
            let size = (SIDE, SIDE);
            super::refuse_useless_unseen(&args.refusal, format, &frame.scene, methods, size)?;
        }
        let mut scene = frame.scene.clone();
        scene.pixels = found;
        let request = Request::new(scene.desc(), (SIDE, SIDE), methods);
        let pixels = prepare(format, &request)?.rgb565_frame(presentation, &mut |_, _| {})?;
        let paced = estimate::frame(args.target, format, &request.desc, methods)
            .ok()
            .flatten()
            .map(|e| Duration::from_secs_f64(e.time(presentation.order).frame));
        Ok((pixels, paced))
    };
    let drawn = frames
        .par_iter()
        .enumerate()
        .map(|(k, frame)| draw(frame).with_context(|| format!("frame {k} of {}", named.name)))
        .collect::<Vec<Result<_>>>()
        // The first frame refused, in the path's order (the frames are drawn in any).
        .into_iter()
        .collect::<Result<Vec<_>>>()?;
    let loop_seconds: Option<f64> = drawn.iter().map(|(_, t)| t.map(|t| t.as_secs_f64())).sum();
    say!(
        "{}'s {} frames in {} on the {}, rows {}, dither {}: {}",
        named.name,
        frames.len(),
        crate::analysis::with_pixels(format, found),
        args.target.board().name,
        presentation.order.name(),
        presentation.dither.name(),
        loop_seconds.map_or_else(
            || "no estimate to pace them by".to_owned(),
            |s| format!(
                "about {s:.1} s a loop ({:.2} frames a second), estimated as for a still frame",
                frames.len() as f64 / s
            )
        )
    )?;
    if !args.headless {
        let shown: Vec<(Vec<u16>, Option<Duration>)> = drawn.clone();
        window::play(&named.name, &shown)?;
    }
    // At the board's pace where every frame has an estimate, else at the path's own.
    let paced: Option<Vec<Duration>> = drawn.iter().map(|(_, t)| *t).collect();
    let held = paced.unwrap_or_else(|| vec![super::frame_time(animation.fps); drawn.len()]);
    let images: Vec<_> = drawn
        .iter()
        .map(|(pixels, _)| rgb565_image(pixels, SIDE))
        .collect();
    let gif = args.output.with_extension("gif");
    super::save_gif(images.iter().zip(held), &gif)?;
    say!(
        "wrote {} ({} frames, {})",
        gif.display(),
        images.len(),
        loop_seconds.map_or_else(
            || format!("at the path's {} a second", animation.fps),
            |_| "each held as long as the board takes to draw it".to_owned()
        )
    )?;
    Ok(())
}

/// The live window, where the simulator has SDL2 to open one.
#[cfg(feature = "window")]
mod window {
    use crate::render::AnyFormat;
    use anyhow::Result;
    use embedded_graphics::pixelcolor::Rgb565;
    use embedded_graphics::pixelcolor::raw::RawU16;
    use embedded_graphics::prelude::*;
    use embedded_graphics_simulator::{
        OutputSettingsBuilder, SimulatorDisplay, SimulatorEvent, Window,
    };
    use obscura::Presentation;
    use obscura_scene::firmware::SIDE;
    use std::time::{Duration, Instant};

    /// Draws the frame into a window, each traced row when the board would have it after
    /// `frame_time` (at once without one), then keeps the window open until it is closed.
    pub fn show(
        title: &str,
        prepared: &dyn AnyFormat,
        presentation: Presentation,
        frame_time: Option<Duration>,
    ) -> Result<Vec<u16>> {
        let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(SIDE, SIDE));
        let mut window = Window::new(
            &format!("obscura preview: {title}"),
            &OutputSettingsBuilder::new().scale(2).build(),
        );
        window.set_max_fps(1000);
        let row_time = frame_time.map_or(Duration::ZERO, |t| t / SIDE);
        let start = Instant::now();
        let mut traced = 0;
        let pixels = prepared.rgb565_frame(presentation, &mut |frame, rows| {
            traced += 1;
            if let Some(wait) = (start + row_time * traced).checked_duration_since(Instant::now()) {
                std::thread::sleep(wait);
            }
            for y in rows {
                for x in 0..SIDE {
                    let raw = frame.get((y * SIDE + x) as usize).copied().unwrap_or(0);
                    let point = Point::new(x as i32, y as i32);
                    let _ = Pixel(point, Rgb565::from(RawU16::new(raw))).draw(&mut display);
                }
            }
            window.update(&display);
        })?;
        'open: loop {
            window.update(&display);
            if window.events().any(|e| e == SimulatorEvent::Quit) {
                break 'open;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        Ok(pixels)
    }

    /// Shows each of `frames` for its time (at once without one), over and over, until the
    /// window is closed.
    pub fn play(title: &str, frames: &[(Vec<u16>, Option<Duration>)]) -> Result<()> {
        let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(SIDE, SIDE));
        let mut window = Window::new(
            &format!("obscura preview: {title}"),
            &OutputSettingsBuilder::new().scale(2).build(),
        );
        for (pixels, time) in frames.iter().cycle() {
            let shown_at = Instant::now();
            for (i, &raw) in pixels.iter().enumerate() {
                let (x, y) = (i as u32 % SIDE, i as u32 / SIDE);
                let point = Point::new(x as i32, y as i32);
                let _ = Pixel(point, Rgb565::from(RawU16::new(raw))).draw(&mut display);
            }
            let until = shown_at + time.unwrap_or(Duration::from_millis(100));
            while Instant::now() < until {
                window.update(&display);
                if window.events().any(|e| e == SimulatorEvent::Quit) {
                    return Ok(());
                }
                std::thread::sleep(Duration::from_millis(20));
            }
        }
        Ok(())
    }
}

/// Built without SDL2, there is no window.
#[cfg(not(feature = "window"))]
mod window {
    use crate::render::AnyFormat;
    use anyhow::{Result, bail};
    use obscura::Presentation;
    use std::time::Duration;

    pub fn show(
        _: &str,
        _: &dyn AnyFormat,
        _: Presentation,
        _: Option<Duration>,
    ) -> Result<Vec<u16>> {
        bail!(NO_WINDOW)
    }

    pub fn play(_: &str, _: &[(Vec<u16>, Option<Duration>)]) -> Result<()> {
        bail!(NO_WINDOW)
    }

    const NO_WINDOW: &str = "this obscura was built without a window: pass --headless, or \
                             build it with `--features window` (which needs SDL2: sudo apt-get \
                             install libsdl2-dev)";
}
