//! One module per subcommand; this one dispatches and holds what they share.

mod analyze;
mod animate;
mod bench;
mod book;
mod chart;
mod compare;
mod emulate;
mod firmware;
mod fuzz;
mod preview;
mod render;
mod stress;

use crate::analysis::{self, Aim, Analysis, Choice, pick};
use crate::cli::{BoardFrameArgs, Command, RefusalArgs, SceneArgs};
use crate::cost::Machine;
use crate::output::say;
use crate::render::{Request, all_cores, prepare, prepare_reference};
use anyhow::{Context, Result, bail};
use image::RgbImage;
use obscura::scenes;
use obscura::{Methods, Pixels};
use obscura_scene::{Format, FormatChoice, NamedScene, OwnedScene, Sampling};

/// Runs a subcommand.
pub fn run(command: Command) -> Result<()> {
    match command {
        Command::Scenes => {
            for scene in &scenes::BUILT_IN {
                say!("{:10} {}", scene.name, scene.summary)?;
            }
            say!(
                "(every command that takes a scene takes a TOML scene file as well; host/scenes/ has examples)"
            )?;
            Ok(())
        }
        Command::Settings => {
            say!("{}", obscura_scene::settings_table().trim_end())?;
            Ok(())
        }
        Command::Analyze(args) => analyze::run(&args),
        Command::Render(args) => render::run(&args),
        Command::Compare(args) => compare::run(&args),
        Command::Animate(args) => animate::run(&args),
        Command::Bench(args) => bench::run(&args),
        Command::Book(args) => book::run(&args),
        Command::Firmware(args) => firmware::run(&args),
        Command::Preview(args) => preview::run(&args),
        Command::Emulate(args) => emulate::run(&args),
        Command::Chart(args) => chart::run(&args),
        Command::Stress(args) => stress::run(&args),
        Command::Fuzz(args) => fuzz::run(&args),
        Command::Teapot(args) => {
            let mesh = crate::teapot::teapot(usize::from(args.steps));
            std::fs::write(&args.output, mesh.obj_text())
                .with_context(|| format!("cannot write {}", args.output.display()))?;
            say!(
                "wrote the teapot at {} steps a patch to {}: {} triangles on {} vertices",
                args.steps,
                args.output.display(),
                mesh.triangles.len(),
                mesh.vertices.len()
            )?;
            Ok(())
        }
    }
}

/// A scene from the command line, ready to render.
pub struct Resolved {
    /// The scene's name.
    pub name: String,
    /// The format to render it in.
    pub format: Format,
    /// The scene, rescaled where the format holds it only so.
    pub scene: OwnedScene,
    /// The methods.
    pub methods: Methods,
}

/// Loads the scene `name` names, with the sample counts `sampling` gives, and runs `command`
/// on it; a refusal of its build is placed at its line and column when the scene came from a
/// file.
pub fn on_scene(
    name: &str,
    sampling: &Sampling,
    command: impl FnOnce(&NamedScene) -> Result<()>,
) -> Result<()> {
    let mut named = obscura_scene::load(name)?;
    sampling.apply(&mut named.scene);
    command(&named).map_err(|error| named.locate(error))
}

/// The format a firmware computes in by `choice`, and the pixels it finds: the format given
/// (f64 refused: it stays on the host) with the scenes' own pixels, or with `auto` the cheapest
/// on `machine` that holds every scene as it is and reaches `target_psnr` on each
/// ([`analysis::firmware_format`]), with adaptive pixels where they are cheaper there, reach it
/// and `choose_pixels` ([`chooses_pixels`]); said aloud on standard error.
pub fn firmware_format(
    choice: FormatChoice,
    scenes: &[NamedScene],
    methods: Methods,
    (machine, target_psnr): (Machine, f64),
    choose_pixels: bool,
) -> Result<(Format, Pixels)> {
    let own = scenes.first().map_or(Pixels::Exact, |s| s.scene.pixels);
    match choice {
        FormatChoice::Given(Format::F64) => bail!(
            "a firmware computes in {}, not f64 (which stays on the host)",
            Format::firmware_names()
        ),
        FormatChoice::Given(format) => Ok((format, own)),
        FormatChoice::Auto => {
            let aim = Aim {
                machine,
                target_psnr,
                rescale: false,
                choose_pixels,
            };
            let pick = analysis::firmware_format(scenes, methods, aim)?;
            eprintln!(
                "--format auto: {} is the cheapest on {machine} that reaches {target_psnr} dB on \
                 every scene (measured on the host, whose frames are the firmware's)",
                pick.named()
            );
            Ok((pick.format, pick.pixels))
        }
    }
}

/// The format a board draws the still scene `named` in by `frame`'s arguments on `machine`
/// ([`firmware_format`]), and the scene with the pixels that format takes.
pub fn board_scene(
    frame: &BoardFrameArgs,
    named: &NamedScene,
    machine: Machine,
) -> Result<(Format, OwnedScene)> {
    let (format, pixels) = firmware_format(
        frame.format,
        std::slice::from_ref(named),
        frame.methods.methods(),
        (machine, frame.target_psnr),
        chooses_pixels(&frame.sampling, std::iter::once(&named.scene)),
    )?;
    let mut scene = named.scene.clone();
    scene.pixels = pixels;
    Ok((format, scene))
}

/// Whether `--format auto` may choose the pixels of `scenes`: where `--pixels` is not given
/// and every scene's are exact (a scene file that asks for adaptive pixels keeps them).
pub fn chooses_pixels<'a>(
    sampling: &Sampling,
    mut scenes: impl Iterator<Item = &'a OwnedScene>,
) -> bool {
    sampling.pixels.is_none() && scenes.all(|scene| scene.pixels == Pixels::Exact)
}

/// Picks the format for `named` by `args`: the format given, or with `auto` the cheapest that
/// holds the scene and measures at the target on the host (rescaled about the eye when only
/// that fits), said aloud on standard error.
pub fn resolve(named: &NamedScene, args: &SceneArgs) -> Result<Resolved> {
    let methods = args.methods.methods();
    let (format, scene) = pick_format(named, args)?;
    Ok(Resolved {
        name: named.name.clone(),
        format,
        scene,
        methods,
    })
}

/// Refuses `drawn`, the image of `scene` by `methods` in a format given, where it measures
/// below `refusal`'s floor against f64 ([`analysis::refuse_useless`]), unless told `--force`;
/// and where f64 cannot draw the scene, which leaves nothing to check it by. `truth` is f64's
/// image where the command has drawn it already. (A format `auto` picks was measured to reach
/// its target.)
pub fn refuse_useless(
    refusal: &RefusalArgs,
    format: Format,
    scene: &OwnedScene,
    methods: Methods,
    drawn: &RgbImage,
    truth: Option<&RgbImage>,
) -> Result<()> {
    if refusal.force || format == Format::F64 {
        return Ok(());
    }
    let request = Request::new(scene.desc(), drawn.dimensions(), methods);
    let rendered;
    let truth = match truth {
        Some(truth) => truth,
        None => {
            rendered = prepare_reference(&request)
                .and_then(|f64s| f64s.render(all_cores(), Some("drawing f64 to check it by")))
                .with_context(|| {
                    format!(
                        "{format} by {methods} holds the scene, but the f64 reference does not, \
                         so nothing can check what {format} draws; change the scene until f64 \
                         holds it (`obscura analyze` says how), or give --force to draw it \
                         unchecked"
                    )
                })?;
            &rendered
        }
    };
    analysis::refuse_useless(format, scene, methods, [drawn, truth], refusal.refuse_below)
}

/// [`refuse_useless`] for a command that draws elsewhere (in a window, on a board): draws the
/// image on the host first, at `size`, where the format builds the scene.
pub fn refuse_useless_unseen(
    refusal: &RefusalArgs,
    format: Format,
    scene: &OwnedScene,
    methods: Methods,
    size: (u32, u32),
) -> Result<()> {
    if refusal.force || format == Format::F64 {
        return Ok(());
    }
    let request = Request::new(scene.desc(), size, methods);
    // A format that cannot build the scene passes: the command's own build says why.
    let Ok(prepared) = prepare(format, &request) else {
        return Ok(());
    };
    let drawn = prepared.render(all_cores(), None)?;
    refuse_useless(refusal, format, scene, methods, &drawn, None)
}

/// The format to render `named` in as `args` ask, and the scene to render.
fn pick_format(named: &NamedScene, args: &SceneArgs) -> Result<(Format, OwnedScene)> {
    let (methods, (width, height), auto) = (args.methods.methods(), args.size, &args.auto);
    let FormatChoice::Given(format) = args.format else {
        let analysis = Analysis::fits(&named.scene, methods, width, height)?;
        let aim = Aim {
            machine: auto.cost_on,
            target_psnr: auto.target_psnr,
            rescale: true,
            choose_pixels: chooses_pixels(&args.sampling, std::iter::once(&named.scene)),
        };
        let picked = pick(&[(&named.scene, &analysis)], methods, (width, height), aim)?;
        let Choice::Reaches(pick) = picked else {
            bail!(
                "{} at {width}x{height}: {} (`obscura analyze {}` says more)",
                named.name,
                picked.shortfall(auto.target_psnr).unwrap_or_default(),
                named.name
            );
        };
        eprintln!(
            "--format auto: {} is the cheapest on {} that reaches {} dB ({:.1} dB measured on \
             the host)",
            pick.named(),
            auto.cost_on,
            auto.target_psnr,
            pick.psnr_db
        );
        if let Some(factor) = pick.rescaled {
            eprintln!(
                "--format auto: {} holds {} only rescaled by {factor} about the eye (the image \
                 is the same); rendering it so",
                pick.format, named.name
            );
        }
        return Ok((pick.format, pick.scene(&named.scene)));
    };
    Ok((format, named.scene.clone()))
}

/// Writes a PNG, saying which file could not be written.
pub fn save(image: &RgbImage, path: &std::path::Path) -> Result<()> {
    use anyhow::Context;
    image
        .save(path)
        .with_context(|| format!("cannot write {}", path.display()))
}

/// Writes `frames` as a GIF to `path` that loops for ever, each frame held for its duration
/// (to the GIF's hundredth of a second).
pub fn save_gif<'a>(
    frames: impl IntoIterator<Item = (&'a RgbImage, std::time::Duration)>,
    path: &std::path::Path,
) -> Result<()> {
    use anyhow::Context;
    use image::codecs::gif::{GifEncoder, Repeat};
    let cannot = || format!("cannot write {}", path.display());
    let file = std::fs::File::create(path).with_context(cannot)?;
    let mut encoder = GifEncoder::new_with_speed(std::io::BufWriter::new(file), 10);
    encoder.set_repeat(Repeat::Infinite).with_context(cannot)?;
    for (frame, held) in frames {
        let rgba = image::DynamicImage::ImageRgb8(frame.clone()).into_rgba8();
        let delay = image::Delay::from_saturating_duration(held);
        encoder
            .encode_frame(image::Frame::from_parts(rgba, 0, 0, delay))
            .with_context(cannot)?;
    }
    Ok(())
}

/// A frame's time at `fps` frames a second.
pub fn frame_time(fps: u16) -> std::time::Duration {
    std::time::Duration::from_secs(1) / u32::from(fps.max(1))
}
