//! `obscura preview`: the firmware's render loop on the desktop. The same core draws the scene
//! at the display's size in RGB565, in the firmware's row order and dither, into an
//! embedded-graphics-simulator window, each row appearing when it would on the target's board
//! (paced by [`estimate::frame`]: the Black Pill for the M4F, the Pico for the M0); the final
//! frame, the firmware's to the bit, is written as a PNG. With `--headless` there is no window
//! and no pace.

use crate::cli::PreviewArgs;
use crate::cost::Machine;
use crate::estimate;
use crate::output::say;
use crate::render::{Request, prepare, rgb565_image};
use anyhow::Result;
use obscura::methods::MethodName;
use obscura_scene::firmware::SIDE;
use obscura_scene::{FormatChoice, NamedScene};
use std::time::Duration;

pub fn run(args: &PreviewArgs) -> Result<()> {
    crate::output::check_file(&args.output)?;
    super::on_scene(&args.scene, &args.sampling, |named| preview(args, named))
}

fn preview(args: &PreviewArgs, named: &NamedScene) -> Result<()> {
    let methods = args.methods.methods();
    let machine = Machine::from(args.target);
    let format = super::firmware_format(
        args.format,
        std::slice::from_ref(named),
        methods,
        machine,
        args.target_psnr,
    )?;
    if let FormatChoice::Given(format) = args.format {
        super::refuse_useless_unseen(&args.refusal, format, &named.scene, methods, (SIDE, SIDE))?;
    }
    let desc = named.scene.desc();
    let request = Request {
        desc: &desc,
        width: SIDE,
        height: SIDE,
        methods,
    };
    let prepared = prepare(format, &request)?;
    let presentation = args.presentation.presentation();
    // An estimate that cannot be made (its pricing scene's files gone from an installed
    // harness's workspace) leaves the frame unpaced, not undrawn.
    let estimate = estimate::frame(args.target, format, &desc, methods);
    say!(
        "{} in {format} on the {}, rows {}, dither {}: {}",
        named.name,
        args.target.board().name,
        presentation.order.name(),
        presentation.dither.name(),
        match &estimate {
            Ok(Some(e)) => format!(
                "about {:.1} s a frame ({:.0} instructions, {:.0} cycles a pixel, {} core{} at \
                 {} MHz), estimated by the instructions and cycles an operation takes in `{}` in \
                 {} under QEMU (`obscura firmware` measures it)",
                e.seconds,
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
        .map(|e| Duration::from_secs_f64(e.seconds));
    let pixels = if args.headless {
        prepared.rgb565_frame(presentation, &mut |_, _| {})?
    } else {
        window::show(&named.name, prepared.as_ref(), presentation, frame_time)?
    };
    super::save(&rgb565_image(&pixels, SIDE), &args.output)?;
    say!("wrote {}", args.output.display())?;
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
        bail!(
            "this obscura was built without a window: pass --headless, or build it with \
             `--features window` (which needs SDL2: sudo apt-get install libsdl2-dev)"
        )
    }
}
