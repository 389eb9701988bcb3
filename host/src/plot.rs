//! Charts drawn with plotters, as SVG and PNG: the speed–accuracy chart of `obscura chart` and
//! the stability chart of `obscura stress`. Text is set in DejaVu Sans, embedded, so the PNG
//! looks the same on every machine.

use anyhow::{Context as _, Result, anyhow};
use plotters::coord::Shift;
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::ops::Range;
use std::path::Path;
use std::sync::OnceLock;

/// One render on the speed–accuracy chart: a scene in a format by some methods, what it cost
/// and how far it is from the f64 reference.
#[derive(Clone, Debug, PartialEq)]
pub struct SpeedPoint {
    /// The scene's name ("whitted", "shapes").
    pub scene: String,
    /// The format's name ("i16f16", "f32", ...).
    pub format: String,
    /// The variant of the methods: "lecture" for the lecture's, else the one method changed,
    /// e.g. "sphere=stable".
    pub variant: String,
    /// Instructions per pixel on the Cortex-M4F, if measured.
    pub m4f_instructions_per_pixel: Option<f64>,
    /// Instructions per pixel on the Cortex-M0, if measured.
    pub m0_instructions_per_pixel: Option<f64>,
    /// Host time per pixel, single thread, in nanoseconds.
    pub host_ns_per_pixel: f64,
    /// PSNR against f64 in dB; infinite for an identical image.
    pub psnr_db: f64,
    /// Pixels whose primary ray hit another object than in f64, in percent.
    pub object_mismatch_pct: f64,
}

/// One line on the stability chart: a format (and method) across a stressed parameter.
#[derive(Clone, Debug, PartialEq)]
pub struct StabilitySeries {
    /// The stress case, one panel each.
    pub case: String,
    /// What the x axis is ("r / |o − c|", "scale", ...).
    pub x_label: String,
    /// What the y axis is ("misclassified rays (%)", ...).
    pub y_label: String,
    /// Whether the x axis is logarithmic.
    pub log_x: bool,
    /// The format.
    pub format: String,
    /// The method, where the case compares methods ("" where it does not).
    pub method: String,
    /// (x, y) per stressed value; `None` where the scene was refused up front.
    pub points: Vec<(f64, Option<f64>)>,
}

/// Draws the speed–accuracy chart to `svg` and `png`.
pub fn speed_accuracy(points: &[SpeedPoint], svg: &Path, png: &Path) -> Result<()> {
    write_both(&SpeedChart::new(points), svg, png)
}

impl StabilitySeries {
    /// The line's label: the format, and the method where the case compares methods.
    pub fn label(&self) -> String {
        if self.method.is_empty() {
            self.format.clone()
        } else {
            format!("{} {}", self.format, self.method)
        }
    }
}

/// Draws series across a parameter, a panel per case, titled `title`, to `svg` and `png`: the
/// stability chart, and the chart's samples axis.
pub fn stability(title: &str, series: &[StabilitySeries], svg: &Path, png: &Path) -> Result<()> {
    write_both(&StabilityChart::new(title, series), svg, png)
}

/// A drawing error of any backend, as plotters reports it.
type DrawResult<DB> =
    std::result::Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// The font family every text is set in; DejaVu Sans is registered under it.
const FONT: &str = "sans-serif";

/// Registers DejaVu Sans as the sans-serif font, once: plotters needs a registered font both to
/// lay out text (SVG and PNG) and to rasterise it (PNG).
fn register_font() -> Result<()> {
    static REGISTERED: OnceLock<std::result::Result<(), String>> = OnceLock::new();
    REGISTERED
        .get_or_init(|| {
            plotters::style::register_font(FONT, FontStyle::Normal, dejavu::sans::regular())
                .map_err(|_| "DejaVu Sans could not be read as a font".to_string())
        })
        .clone()
        .map_err(anyhow::Error::msg)
}

/// A chart that can be drawn on any plotters backend.
trait Chart {
    /// Width and height in pixels.
    fn size(&self) -> (u32, u32);
    /// Draws the whole chart on `root`.
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB>;
}

/// Draws `chart` once as SVG and once as PNG.
fn write_both(chart: &impl Chart, svg: &Path, png: &Path) -> Result<()> {
    register_font()?;
    let size = chart.size();
    {
        let root = SVGBackend::new(svg, size).into_drawing_area();
        chart
            .draw(&root)
            .map_err(|e| anyhow!("{e}"))
            .with_context(|| format!("drawing {}", svg.display()))?;
        root.present()
            .map_err(|e| anyhow!("{e}"))
            .with_context(|| format!("writing {}", svg.display()))?;
    }
    {
        let root = BitMapBackend::new(png, size).into_drawing_area();
        chart
            .draw(&root)
            .map_err(|e| anyhow!("{e}"))
            .with_context(|| format!("drawing {}", png.display()))?;
        root.present()
            .map_err(|e| anyhow!("{e}"))
            .with_context(|| format!("writing {}", png.display()))?;
    }
    Ok(())
}

/// Colours for formats and series, in order of first appearance (Tableau 10).
const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// A series' marker: a filled circle for its case's first method, a ring for the second, a
/// triangle for the third.
fn marker<DB: DrawingBackend, C: Clone + 'static>(
    style: usize,
    at: C,
    colour: RGBColor,
) -> DynElement<'static, DB, C> {
    match style {
        0 => Circle::new(at, 4, colour.filled()).into_dyn(),
        1 => Circle::new(at, 5, colour.stroke_width(2)).into_dyn(),
        _ => TriangleMarker::new(at, 6, colour.filled()).into_dyn(),
    }
}

/// The `i`th colour of the palette, cycling.
fn colour(i: usize) -> RGBColor {
    PALETTE.get(i % PALETTE.len()).copied().unwrap_or(BLACK)
}

/// The distinct names, in order of first appearance.
fn first_appearance<'a>(names: impl IntoIterator<Item = &'a str>) -> Vec<&'a str> {
    let mut distinct: Vec<&str> = Vec::new();
    for name in names {
        if !distinct.contains(&name) {
            distinct.push(name);
        }
    }
    distinct
}

/// Where `name` is in `names`; 0 if it is not there.
fn index_of(names: &[&str], name: &str) -> usize {
    names.iter().position(|n| *n == name).unwrap_or(0)
}

/// `v` with three significant digits at most, without trailing zeros.
fn significant(v: f64) -> String {
    let magnitude = if v == 0.0 {
        0
    } else {
        v.abs().log10().floor() as i32
    };
    let decimals = (2 - magnitude).clamp(0, 9) as usize;
    let text = format!("{v:.decimals$}");
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    }
}

/// A short axis label for `v`: "500", "20k", "1e-6".
fn compact(v: f64) -> String {
    let a = v.abs();
    if v == 0.0 || !v.is_finite() {
        format!("{v}")
    } else if !(1e-2..1e6).contains(&a) {
        format!("{v:.1e}").replace(".0e", "e")
    } else if a >= 1e3 {
        format!("{}k", significant(v / 1e3))
    } else {
        significant(v)
    }
}

/// A logarithmic axis around `min..=max` (both positive), with the key-point hint and the
/// mantissas to label. Plotters only places key points on a log axis from the first power of ten
/// inside the range upwards, so a range narrower than two decades is widened to whole decades.
#[derive(Clone, Copy, Debug)]
struct LogAxis {
    /// The lowest value shown.
    lo: f64,
    /// The highest value shown.
    hi: f64,
    /// How many key points to ask plotters for.
    hint: usize,
    /// Whether to label 2× and 5× the powers of ten too.
    label_2_5: bool,
}

impl LogAxis {
    /// The axis for positive values from `min` to `max`, with some room either side.
    fn new(min: f64, max: f64) -> Self {
        // Room either side: 4 % of the width, at least a factor of 1.26.
        let pad = 10f64.powf((0.04 * (max / min).log10()).max(0.1));
        let (lo, hi) = (min / pad, max * pad);
        let span = (hi / lo).log10();
        let (lo, hi, decades) = if span >= 2.0 {
            // Two powers of ten at least inside: enough labels without snapping.
            (lo, hi, span.ceil())
        } else {
            // Snapped to whole decades, a hair outside so rounding never drops the first or
            // last power of ten.
            let lo_exp = (min / 1.1).log10().floor();
            let hi_exp = (max * 1.1).log10().ceil().max(lo_exp + 1.0);
            (
                10f64.powf(lo_exp) * 0.999,
                10f64.powf(hi_exp) * 1.001,
                hi_exp - lo_exp,
            )
        };
        let decades = decades as usize;
        LogAxis {
            lo,
            hi,
            hint: if decades <= 4 { decades * 10 } else { decades },
            label_2_5: decades <= 3,
        }
    }

    /// The axis for the positive finite values among `values`; one decade if there are none.
    fn around(values: impl IntoIterator<Item = f64>) -> Self {
        let (min, max) = values
            .into_iter()
            .filter(|v| v.is_finite() && *v > 0.0)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                (lo.min(v), hi.max(v))
            });
        if min <= max {
            LogAxis::new(min, max)
        } else {
            LogAxis::new(1.0, 9.0)
        }
    }

    /// The label of key point `v`: empty between the labelled multiples of powers of ten.
    fn label(&self, v: f64) -> String {
        if v.is_nan() || v <= 0.0 {
            return String::new();
        }
        let mantissa = v / 10f64.powf(v.log10().floor());
        let rounded = mantissa.round();
        let labelled = (mantissa - rounded).abs() < 1e-6
            && (rounded == 1.0 || (self.label_2_5 && (rounded == 2.0 || rounded == 5.0)));
        if labelled { compact(v) } else { String::new() }
    }
}

/// The text style of titles, labels and notes at `size` pixels.
fn text_style(size: u32) -> TextStyle<'static> {
    (FONT, size).into_text_style(&(1, 1))
}

/// Draws an empty panel: `title` and, in the middle, `note`.
fn empty_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
    note: &str,
) -> DrawResult<DB> {
    let inner = area.titled(title, text_style(18))?;
    let (w, h) = inner.dim_in_pixel();
    let style = text_style(16)
        .color(&RGBColor(110, 110, 110))
        .pos(Pos::new(HPos::Center, VPos::Center));
    inner.draw_text(note, &style, (w as i32 / 2, h as i32 / 2))
}

// ---------------------------------------------------------------------------------------------
// Speed–accuracy chart.

/// A cost axis of the speed–accuracy chart: one column of panels.
#[derive(Clone, Copy, Debug)]
struct CostColumn {
    /// The axis label.
    name: &'static str,
    /// The name in panel titles.
    short: &'static str,
    /// The cost of a point on this axis, if measured.
    cost: fn(&SpeedPoint) -> Option<f64>,
}

/// The three cost columns, left to right.
const COLUMNS: [CostColumn; 3] = [
    CostColumn {
        name: "Cortex-M4F instructions / pixel",
        short: "Cortex-M4F instructions/pixel",
        cost: |p| p.m4f_instructions_per_pixel,
    },
    CostColumn {
        name: "Cortex-M0 instructions / pixel",
        short: "Cortex-M0 instructions/pixel",
        cost: |p| p.m0_instructions_per_pixel,
    },
    CostColumn {
        name: "host ns / pixel (1 thread)",
        short: "host ns/pixel",
        cost: |p| Some(p.host_ns_per_pixel),
    },
];

/// What a row of panels measures accuracy by.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Metric {
    /// PSNR against f64, higher is better.
    Psnr,
    /// Object mismatch against f64, lower is better.
    Mismatch,
}

/// One row of the speed–accuracy chart: a scene and a metric, with the y axis all its panels
/// share.
#[derive(Clone, Debug)]
struct AccuracyRow<'a> {
    /// The scene.
    scene: &'a str,
    /// The accuracy measure.
    metric: Metric,
    /// The y axis range.
    y: Range<f64>,
    /// Where an infinite PSNR is drawn, if any point has one.
    ceiling: Option<f64>,
}

impl<'a> AccuracyRow<'a> {
    /// The row of `scene`'s points by `metric`.
    fn new(scene: &'a str, metric: Metric, points: &[&SpeedPoint]) -> Self {
        match metric {
            Metric::Psnr => {
                let finite: Vec<f64> = points
                    .iter()
                    .map(|p| p.psnr_db)
                    .filter(|v| v.is_finite())
                    .collect();
                let any_infinite = points.iter().any(|p| p.psnr_db == f64::INFINITY);
                let (min, max) = min_max(&finite).unwrap_or((30.0, 50.0));
                let ceiling = any_infinite.then_some(max + 10.0);
                let top = ceiling.unwrap_or(max);
                let pad = ((top - min) * 0.06).max(1.0);
                AccuracyRow {
                    scene,
                    metric,
                    y: (min - pad)..(top + pad),
                    ceiling,
                }
            }
            Metric::Mismatch => {
                let values: Vec<f64> = points
                    .iter()
                    .map(|p| p.object_mismatch_pct)
                    .filter(|v| v.is_finite())
                    .collect();
                let (min, max) = min_max(&values).unwrap_or((0.0, 0.0));
                let lo = min.min(0.0);
                let hi = if max > lo {
                    max + (max - lo) * 0.1
                } else {
                    lo + 0.1
                };
                AccuracyRow {
                    scene,
                    metric,
                    y: lo..hi,
                    ceiling: None,
                }
            }
        }
    }

    /// The y axis label.
    fn y_desc(&self) -> String {
        match (self.metric, self.ceiling) {
            (Metric::Psnr, Some(_)) => "PSNR vs f64 (dB, higher is better; ∞ drawn at top)".into(),
            (Metric::Psnr, None) => "PSNR vs f64 (dB, higher is better)".into(),
            (Metric::Mismatch, _) => "object mismatch vs f64 (%, lower is better)".into(),
        }
    }

    /// The short name of the metric in titles.
    fn name(&self) -> &'static str {
        match self.metric {
            Metric::Psnr => "PSNR",
            Metric::Mismatch => "object mismatch",
        }
    }

    /// Where `p` is drawn, and its error for the Pareto front; `None` if it cannot be drawn.
    fn place(&self, p: &SpeedPoint) -> Option<(f64, f64)> {
        match self.metric {
            Metric::Psnr if p.psnr_db.is_finite() => Some((p.psnr_db, -p.psnr_db)),
            Metric::Psnr if p.psnr_db == f64::INFINITY => {
                self.ceiling.map(|c| (c, f64::NEG_INFINITY))
            }
            Metric::Psnr => None,
            Metric::Mismatch if p.object_mismatch_pct.is_finite() => {
                Some((p.object_mismatch_pct, p.object_mismatch_pct))
            }
            Metric::Mismatch => None,
        }
    }
}

/// The smallest and largest of `values`, `None` if empty.
fn min_max(values: &[f64]) -> Option<(f64, f64)> {
    values.iter().fold(None, |acc, &v| match acc {
        None => Some((v, v)),
        Some((lo, hi)) => Some((v.min(lo), v.max(hi))),
    })
}

/// A point as drawn in one panel.
#[derive(Clone, Debug)]
struct PanelPoint {
    /// The cost.
    x: f64,
    /// Where on the y axis.
    y: f64,
    /// The error for the Pareto front, lower is better.
    error: f64,
    /// Index of the format, for its colour.
    format: usize,
    /// Whether it is the lecture's methods.
    lecture: bool,
    /// "format variant".
    label: String,
}

/// The speed–accuracy chart, ready to draw.
#[derive(Debug)]
struct SpeedChart<'a> {
    /// All points.
    points: &'a [SpeedPoint],
    /// The scenes, in order of first appearance.
    scenes: Vec<&'a str>,
    /// The formats, in order of first appearance: their colours.
    formats: Vec<&'a str>,
}

/// Height of the speed–accuracy chart's legend strip.
const SPEED_HEADER: u32 = 100;
/// Width of one speed–accuracy panel.
const SPEED_PANEL_W: u32 = 600;
/// Height of one speed–accuracy panel.
const SPEED_PANEL_H: u32 = 475;

impl Chart for SpeedChart<'_> {
    fn size(&self) -> (u32, u32) {
        let rows = (2 * self.scenes.len()).max(1) as u32;
        (
            SPEED_PANEL_W * COLUMNS.len() as u32,
            SPEED_HEADER + SPEED_PANEL_H * rows,
        )
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        root.fill(&WHITE)?;
        let (header, body) = root.split_vertically(SPEED_HEADER);
        self.legend(&header)?;
        if self.scenes.is_empty() {
            return empty_panel(&body, "speed vs accuracy", "no renders to chart");
        }
        let rows: Vec<AccuracyRow<'_>> = self
            .scenes
            .iter()
            .flat_map(|&scene| {
                let points: Vec<&SpeedPoint> =
                    self.points.iter().filter(|p| p.scene == scene).collect();
                [Metric::Psnr, Metric::Mismatch].map(|m| AccuracyRow::new(scene, m, &points))
            })
            .collect();
        let panels = body.split_evenly((rows.len(), COLUMNS.len()));
        let cells = rows
            .iter()
            .flat_map(|row| COLUMNS.iter().map(move |column| (row, column)));
        for (area, (row, column)) in panels.iter().zip(cells) {
            self.panel(area, row, column)?;
        }
        Ok(())
    }
}

impl<'a> SpeedChart<'a> {
    /// The chart of `points`.
    fn new(points: &'a [SpeedPoint]) -> Self {
        SpeedChart {
            points,
            scenes: first_appearance(points.iter().map(|p| p.scene.as_str())),
            formats: first_appearance(points.iter().map(|p| p.format.as_str())),
        }
    }

    /// Draws the title and the legend: formats by colour, markers, front and ceiling.
    fn legend<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let (width, _) = area.dim_in_pixel();
        let width = width as i32;
        area.draw_text(
            "Speed vs accuracy against the f64 reference",
            &text_style(24),
            (20, 10),
        )?;
        let style = text_style(16).pos(Pos::new(HPos::Left, VPos::Center));
        let (mut x, mut y) = (30, 55);
        let mut place = |text: &str, extra: i32| -> std::result::Result<(i32, i32), _> {
            let (w, _) = area.estimate_text_size(text, &style)?;
            let needed = extra + 8 + w as i32 + 26;
            if x + needed > width - 10 && x > 30 {
                x = 30;
                y += 28;
            }
            let at = (x, y);
            x += needed;
            Ok((at.0, at.1))
        };
        for (i, format) in self.formats.iter().enumerate() {
            let (mx, my) = place(format, 12)?;
            area.draw(&Circle::new((mx + 6, my), 6, colour(i).filled()))?;
            area.draw_text(format, &style, (mx + 20, my))?;
        }
        let grey = RGBColor(90, 90, 90);
        let text = "lecture's methods";
        let (mx, my) = place(text, 12)?;
        area.draw(&Circle::new((mx + 6, my), 6, grey.filled()))?;
        area.draw_text(text, &style, (mx + 20, my))?;
        let text = "one method changed";
        let (mx, my) = place(text, 12)?;
        area.draw(&Circle::new((mx + 6, my), 6, grey.stroke_width(2)))?;
        area.draw_text(text, &style, (mx + 20, my))?;
        let text = "Pareto front, labelled \"format variant\"";
        let (mx, my) = place(text, 24)?;
        area.draw(&PathElement::new(
            vec![(mx, my), (mx + 24, my)],
            BLACK.stroke_width(2),
        ))?;
        area.draw_text(text, &style, (mx + 32, my))?;
        if self.points.iter().any(|p| p.psnr_db == f64::INFINITY) {
            let text = "PSNR ∞ (identical to f64) drawn on the dashed line at the top";
            let (mx, my) = place(text, 24)?;
            area.draw(&PathElement::new(
                vec![(mx, my), (mx + 8, my)],
                grey.stroke_width(1),
            ))?;
            area.draw(&PathElement::new(
                vec![(mx + 14, my), (mx + 22, my)],
                grey.stroke_width(1),
            ))?;
            area.draw_text(text, &style, (mx + 32, my))?;
        }
        Ok(())
    }

    /// Draws the panel of `row` against `column`.
    fn panel<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        row: &AccuracyRow<'_>,
        column: &CostColumn,
    ) -> DrawResult<DB> {
        let title = format!("{}: {} vs {}", row.scene, row.name(), column.short);
        let points: Vec<PanelPoint> = self
            .points
            .iter()
            .filter(|p| p.scene == row.scene)
            .filter_map(|p| {
                let x = (column.cost)(p).filter(|x| x.is_finite() && *x > 0.0)?;
                let (y, error) = row.place(p)?;
                Some(PanelPoint {
                    x,
                    y,
                    error,
                    format: index_of(&self.formats, &p.format),
                    lecture: p.variant == "lecture",
                    label: format!("{} {}", p.format, p.variant),
                })
            })
            .collect();
        if points.is_empty() {
            return empty_panel(area, &title, &format!("no {} measured", column.name));
        }

        let axis = LogAxis::around(points.iter().map(|p| p.x));
        let x_label = |v: &f64| axis.label(*v);
        let mut chart = ChartBuilder::on(area)
            .caption(&title, text_style(18))
            .margin(12)
            .margin_right(24)
            .x_label_area_size(48)
            .y_label_area_size(70)
            .build_cartesian_2d((axis.lo..axis.hi).log_scale(), row.y.clone())?;
        chart
            .configure_mesh()
            .x_labels(axis.hint)
            .x_label_formatter(&x_label)
            .x_max_light_lines(1)
            .y_max_light_lines(4)
            .y_label_formatter(&|v| compact(*v))
            .y_labels(8)
            .x_desc(column.name)
            .y_desc(row.y_desc())
            .label_style(text_style(13))
            .axis_desc_style(text_style(14))
            .draw()?;

        if let Some(ceiling) = row.ceiling {
            chart.draw_series(DashedLineSeries::new(
                [(axis.lo, ceiling), (axis.hi, ceiling)],
                6,
                5,
                RGBColor(90, 90, 90).stroke_width(1),
            ))?;
            chart.draw_series(std::iter::once(
                EmptyElement::at((axis.lo, ceiling))
                    + Text::new("∞", (4, -18), text_style(16).color(&RGBColor(90, 90, 90))),
            ))?;
        }

        // The Pareto front, in increasing cost, under the points.
        let pairs: Vec<(f64, f64)> = points.iter().map(|p| (p.x, p.error)).collect();
        let mut front: Vec<&PanelPoint> = points
            .iter()
            .zip(crate::pareto::front(&pairs))
            .filter_map(|(p, on)| on.then_some(p))
            .collect();
        front.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
        chart.draw_series(LineSeries::new(
            front.iter().map(|p| (p.x, p.y)),
            BLACK.mix(0.7).stroke_width(2),
        ))?;

        // Lecture points last, so a filled marker is never hidden under a hollow one.
        let mut order: Vec<&PanelPoint> = points.iter().collect();
        order.sort_by_key(|p| p.lecture);
        chart.draw_series(order.iter().map(|p| {
            let c = colour(p.format);
            let style = if p.lecture {
                c.filled()
            } else {
                c.stroke_width(2)
            };
            Circle::new((p.x, p.y), 5, style)
        }))?;

        // Labels of the front, stacked where points coincide, alternately above and below.
        let label_style = text_style(11).color(&RGBColor(40, 40, 40));
        let mut drawn: Vec<(f64, f64)> = Vec::new();
        let mut labels = Vec::with_capacity(front.len());
        for (i, p) in front.iter().enumerate() {
            let same = drawn.iter().filter(|&&(x, y)| x == p.x && y == p.y).count() as i32;
            let dy = if i % 2 == 0 {
                -16 - 12 * same
            } else {
                6 + 12 * same
            };
            drawn.push((p.x, p.y));
            labels.push(
                EmptyElement::at((p.x, p.y))
                    + Text::new(p.label.clone(), (7, dy), label_style.clone()),
            );
        }
        chart.draw_series(labels)?;
        Ok(())
    }
}

// ---------------------------------------------------------------------------------------------
// Stability chart.

/// Width of one stability panel.
const STABILITY_PANEL_W: u32 = 600;
/// Height of one stability panel.
const STABILITY_PANEL_H: u32 = 450;
/// Height of the stability chart's title strip.
const STABILITY_HEADER: u32 = 50;

/// The stability chart, ready to draw.
#[derive(Debug)]
struct StabilityChart<'a> {
    /// The title.
    title: &'a str,
    /// The series, grouped by case in order of first appearance.
    cases: Vec<(&'a str, Vec<&'a StabilitySeries>)>,
    /// The formats (a label's first word), in order of first appearance: their colours.
    formats: Vec<&'a str>,
    /// Columns of panels.
    columns: usize,
}

impl<'a> StabilityChart<'a> {
    /// The chart of `series`, titled `title`.
    fn new(title: &'a str, series: &'a [StabilitySeries]) -> Self {
        let cases: Vec<(&str, Vec<&StabilitySeries>)> =
            first_appearance(series.iter().map(|s| s.case.as_str()))
                .into_iter()
                .map(|case| (case, series.iter().filter(|s| s.case == case).collect()))
                .collect();
        let columns = match cases.len() {
            0 | 1 => 1,
            2..=4 => 2,
            _ => 3,
        };
        StabilityChart {
            title,
            cases,
            formats: first_appearance(series.iter().map(|s| s.format.as_str())),
            columns,
        }
    }

    /// Rows of panels.
    fn rows(&self) -> usize {
        self.cases.len().div_ceil(self.columns).max(1)
    }

    /// Draws the panel of one case.
    fn panel<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        case: &str,
        series: &[&StabilitySeries],
    ) -> DrawResult<DB> {
        let Some(first) = series.first() else {
            return empty_panel(area, case, "no series");
        };
        let log_x = first.log_x;
        let usable_x = |x: f64| x.is_finite() && (!log_x || x > 0.0);
        let xs: Vec<f64> = series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.0))
            .filter(|&x| usable_x(x))
            .collect();
        let ys: Vec<f64> = series
            .iter()
            .flat_map(|s| {
                s.points
                    .iter()
                    .filter(|p| usable_x(p.0))
                    .filter_map(|p| p.1)
            })
            .filter(|y| y.is_finite())
            .collect();
        let Some((x_min, x_max)) = min_max(&xs) else {
            return empty_panel(area, case, "no stressed values");
        };

        // y: from zero when the values are near it, else around them; below that, a band with
        // one lane per series with refused values, for their crosses.
        let (min, max) = min_max(&ys).unwrap_or((0.0, 1.0));
        let span = if max > min {
            max - min
        } else {
            max.abs().max(1.0)
        };
        let base = if min >= 0.0 && min <= 0.5 * max {
            0.0
        } else {
            min - 0.05 * span
        };
        let top = if max > base {
            max + 0.08 * (max - base)
        } else {
            base + span
        };
        let refusing: Vec<usize> = series
            .iter()
            .enumerate()
            .filter(|(_, s)| s.points.iter().any(|&(x, y)| y.is_none() && usable_x(x)))
            .map(|(i, _)| i)
            .collect();
        let lanes = refusing.len() as f64;
        let lane = (top - base) * 0.05f64.min(0.25 / (lanes + 0.5));
        let bottom = if refusing.is_empty() {
            base
        } else {
            base - lane * (lanes + 0.5)
        };

        // A format keeps its colour across the panels; a method its line and marker within one.
        let methods = first_appearance(series.iter().map(|s| s.method.as_str()));
        let panel = StabilityPanel {
            case,
            series,
            colours: series
                .iter()
                .map(|s| colour(index_of(&self.formats, &s.format)))
                .collect(),
            styles: series
                .iter()
                .map(|s| index_of(&methods, &s.method))
                .collect(),
            usable_x: &usable_x,
            y: bottom..top,
            refusing,
            lane,
            base,
        };
        if log_x {
            let axis = LogAxis::new(x_min, x_max);
            let label = |v: &f64| axis.label(*v);
            panel.draw(area, (axis.lo..axis.hi).log_scale(), axis.hint, &label)
        } else {
            let pad = if x_max > x_min {
                (x_max - x_min) * 0.04
            } else {
                x_min.abs().max(1.0) * 0.1
            };
            let label = |v: &f64| compact(*v);
            panel.draw(area, (x_min - pad)..(x_max + pad), 10, &label)
        }
    }
}

impl Chart for StabilityChart<'_> {
    fn size(&self) -> (u32, u32) {
        (
            STABILITY_PANEL_W * self.columns as u32,
            STABILITY_HEADER + STABILITY_PANEL_H * self.rows() as u32,
        )
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        root.fill(&WHITE)?;
        let (header, body) = root.split_vertically(STABILITY_HEADER);
        header.draw_text(self.title, &text_style(20), (20, 14))?;
        if self.cases.is_empty() {
            return empty_panel(&body, "stability", "no stress cases");
        }
        let panels = body.split_evenly((self.rows(), self.columns));
        for (area, (case, series)) in panels.iter().zip(&self.cases) {
            self.panel(area, case, series)?;
        }
        Ok(())
    }
}

/// One panel of the stability chart, with its y axis worked out.
struct StabilityPanel<'a, 'b> {
    /// The case: the panel's title.
    case: &'b str,
    /// Its series.
    series: &'b [&'a StabilitySeries],
    /// The colour of each series: its format's.
    colours: Vec<RGBColor>,
    /// The line and marker of each series: its method's, 0 to 2.
    styles: Vec<usize>,
    /// Whether an x can be drawn on the x axis.
    usable_x: &'b dyn Fn(f64) -> bool,
    /// The y axis range.
    y: Range<f64>,
    /// The indices of the series with refused values, one lane each below `base`.
    refusing: Vec<usize>,
    /// The height of a lane.
    lane: f64,
    /// The lowest y of values; the refusal lanes are below it.
    base: f64,
}

impl std::fmt::Debug for StabilityPanel<'_, '_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("StabilityPanel")
            .field("case", &self.case)
            .field("series", &self.series)
            .field("y", &self.y)
            .field("refusing", &self.refusing)
            .finish_non_exhaustive()
    }
}

impl StabilityPanel<'_, '_> {
    /// Draws the panel with the x axis `x_spec`, `x_hint` key points labelled by `x_label`.
    fn draw<DB, XS>(
        &self,
        area: &DrawingArea<DB, Shift>,
        x_spec: XS,
        x_hint: usize,
        x_label: &dyn Fn(&f64) -> String,
    ) -> DrawResult<DB>
    where
        DB: DrawingBackend,
        XS: AsRangedCoord<Value = f64>,
        XS::CoordDescType: ValueFormatter<f64>,
    {
        let Some(first) = self.series.first() else {
            return Ok(());
        };
        let mut chart = ChartBuilder::on(area)
            .caption(self.case, text_style(18))
            .margin(12)
            .margin_right(20)
            .x_label_area_size(48)
            .y_label_area_size(70)
            .build_cartesian_2d(x_spec, self.y.clone())?;
        chart
            .configure_mesh()
            .x_labels(x_hint)
            .x_label_formatter(x_label)
            .x_max_light_lines(if first.log_x { 1 } else { 5 })
            .y_max_light_lines(4)
            .y_label_formatter(&|v| compact(*v))
            .y_labels(8)
            .x_desc(first.x_label.as_str())
            .y_desc(first.y_label.as_str())
            .label_style(text_style(13))
            .axis_desc_style(text_style(14))
            .draw()?;

        if !self.refusing.is_empty() {
            let x_range = chart.x_range();
            chart.draw_series(LineSeries::new(
                [(x_range.start, self.base), (x_range.end, self.base)],
                BLACK.mix(0.3).stroke_width(1),
            ))?;
        }

        for (i, ((s, &c), &style)) in self
            .series
            .iter()
            .zip(&self.colours)
            .zip(&self.styles)
            .enumerate()
        {
            // Lines through runs of drawn values, broken where the scene was refused.
            let mut runs: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
            for &(x, y) in s.points.iter().filter(|p| (self.usable_x)(p.0)) {
                match y.filter(|y| y.is_finite()) {
                    Some(y) => runs.last_mut().into_iter().for_each(|run| run.push((x, y))),
                    None if y.is_none() => runs.push(Vec::new()),
                    None => {}
                }
            }
            for run in runs {
                if style == 0 {
                    chart.draw_series(LineSeries::new(run, c.stroke_width(2)))?;
                } else {
                    let (dash, gap) = if style == 1 { (8, 5) } else { (3, 4) };
                    chart.draw_series(DashedLineSeries::new(run, dash, gap, c.stroke_width(2)))?;
                }
            }
            let values = s
                .points
                .iter()
                .filter(|p| (self.usable_x)(p.0))
                .filter_map(|&(x, y)| Some((x, y.filter(|y| y.is_finite())?)));
            chart
                .draw_series(values.map(|xy| marker(style, xy, c)))?
                .label(s.label())
                .legend(move |(x, y)| {
                    EmptyElement::at((x, y))
                        + PathElement::new(vec![(-8, 0), (8, 0)], c.stroke_width(2))
                        + marker(style, (0, 0), c)
                });
            if let Some(k) = self.refusing.iter().position(|&r| r == i) {
                let y = self.base - self.lane * (k as f64 + 1.0);
                let refused = s
                    .points
                    .iter()
                    .filter(|p| p.1.is_none() && (self.usable_x)(p.0))
                    .map(|p| Cross::new((p.0, y), 5, c.stroke_width(2)));
                chart.draw_series(refused)?;
            }
        }
        // The legend goes into the corner with the fewest markers.
        let (px, py) = chart.plotting_area().get_pixel_range();
        let mut crowd = [0usize; 4];
        for s in self.series {
            for &(x, y) in s.points.iter().filter(|p| (self.usable_x)(p.0)) {
                let y = y.filter(|y| y.is_finite()).unwrap_or(self.base - self.lane);
                let (bx, by) = chart.backend_coord(&(x, y));
                let right = bx - px.start > (px.end - px.start) * 55 / 100;
                let left = bx - px.start < (px.end - px.start) * 45 / 100;
                let top = by - py.start < (py.end - py.start) * 45 / 100;
                let bottom = by - py.start > (py.end - py.start) * 55 / 100;
                for (corner, inside) in [top && right, top && left, bottom && right, bottom && left]
                    .iter()
                    .enumerate()
                {
                    if *inside && let Some(count) = crowd.get_mut(corner) {
                        *count += 1;
                    }
                }
            }
        }
        let corners = [
            SeriesLabelPosition::UpperRight,
            SeriesLabelPosition::UpperLeft,
            SeriesLabelPosition::LowerRight,
            SeriesLabelPosition::LowerLeft,
        ];
        // Ties go to the first: upper right, then upper left, ...
        let legend_corner = crowd
            .iter()
            .zip(corners)
            .min_by_key(|(count, _)| **count)
            .map_or(SeriesLabelPosition::UpperRight, |(_, corner)| corner);

        if !self.refusing.is_empty() {
            chart
                .draw_series(std::iter::empty::<Cross<(f64, f64), i32>>())?
                .label("× refused up front")
                .legend(|xy| Cross::new(xy, 5, BLACK.stroke_width(2)));
        }
        chart
            .configure_series_labels()
            .position(legend_corner)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK.mix(0.5))
            .label_font(text_style(13))
            .draw()?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    /// A fresh directory for one test's files.
    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("obscura-plot-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    /// Checks both files exist, the PNG has `size` and the SVG holds `label`.
    fn check(svg: &Path, png: &Path, size: (u32, u32), label: &str) {
        let svg_text = std::fs::read_to_string(svg).unwrap();
        assert!(!svg_text.is_empty());
        assert!(svg_text.contains(label), "{label:?} missing from the SVG");
        assert!(std::fs::metadata(png).unwrap().len() > 0);
        let image = image::open(png).unwrap();
        assert_eq!((image.width(), image.height()), size);
    }

    fn point(scene: &str, format: &str, variant: &str, m4f: f64, psnr: f64) -> SpeedPoint {
        SpeedPoint {
            scene: scene.into(),
            format: format.into(),
            variant: variant.into(),
            m4f_instructions_per_pixel: Some(m4f),
            m0_instructions_per_pixel: None,
            host_ns_per_pixel: m4f / 40.0,
            psnr_db: psnr,
            object_mismatch_pct: if psnr.is_finite() {
                60.0 / psnr - 1.0
            } else {
                0.0
            },
        }
    }

    #[test]
    fn speed_accuracy_draws_both_files() {
        let mut points = vec![
            point("whitted", "i16f16", "lecture", 2_400.0, 38.5),
            point("whitted", "i16f16", "sphere=stable", 2_600.0, 41.0),
            point("whitted", "i32f32", "lecture", 9_800.0, 58.0),
            point("whitted", "f32", "lecture", 4_100.0, f64::INFINITY),
            point("shapes", "i16f16", "lecture", 1_900.0, 35.0),
            point("shapes", "f32", "lecture", 3_900.0, 52.5),
            point("shapes", "f32", "sqrt=approx", 3_000.0, 52.5),
        ];
        points[0].m0_instructions_per_pixel = Some(21_000.0);
        points[6].m4f_instructions_per_pixel = None;
        let dir = scratch("speed");
        let (svg, png) = (dir.join("chart.svg"), dir.join("chart.png"));
        speed_accuracy(&points, &svg, &png).unwrap();
        check(
            &svg,
            &png,
            (1800, 1000 + 1000),
            "whitted: PSNR vs Cortex-M4F instructions/pixel",
        );
        let svg_text = std::fs::read_to_string(&svg).unwrap();
        assert!(svg_text.contains("i16f16 lecture"), "front labels missing");
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn speed_accuracy_survives_no_points() {
        let dir = scratch("speed-empty");
        let (svg, png) = (dir.join("chart.svg"), dir.join("chart.png"));
        speed_accuracy(&[], &svg, &png).unwrap();
        check(&svg, &png, (1800, 575), "no renders to chart");
        let _ = std::fs::remove_dir_all(&dir);
    }

    fn series(
        case: &str,
        log_x: bool,
        format: &str,
        points: &[(f64, Option<f64>)],
    ) -> StabilitySeries {
        StabilitySeries {
            case: case.into(),
            x_label: "r / |o − c|".into(),
            y_label: "misclassified rays (%)".into(),
            log_x,
            format: format.into(),
            method: String::new(),
            points: points.to_vec(),
        }
    }

    #[test]
    fn stability_draws_both_files() {
        let all = [
            series(
                "tiny sphere",
                true,
                "i16f16",
                &[(1e-1, Some(0.0)), (1e-2, Some(0.4)), (1e-3, None)],
            ),
            series(
                "tiny sphere",
                true,
                "f32",
                &[(1e-1, Some(0.0)), (1e-2, Some(0.0)), (1e-3, Some(0.1))],
            ),
            series(
                "far scene",
                false,
                "i16f16",
                &[(1.0, Some(2.0)), (4.0, None), (16.0, None)],
            ),
            series(
                "far scene",
                false,
                "f32",
                &[(1.0, Some(1.0)), (4.0, Some(1.5)), (16.0, Some(3.0))],
            ),
            series("all refused", false, "i16f16", &[(1.0, None), (2.0, None)]),
        ];
        let dir = scratch("stability");
        let (svg, png) = (dir.join("stress.svg"), dir.join("stress.png"));
        stability("stability", &all, &svg, &png).unwrap();
        check(&svg, &png, (1200, 50 + 900), "tiny sphere");
        let svg_text = std::fs::read_to_string(&svg).unwrap();
        assert!(svg_text.contains("refused up front"));
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn unwritable_paths_are_errors_not_panics() {
        let base = scratch("missing");
        let dir = base.join("no such directory");
        let points = [point("whitted", "f32", "lecture", 4_000.0, 50.0)];
        let error = speed_accuracy(&points, &dir.join("c.svg"), &dir.join("c.png")).unwrap_err();
        assert!(format!("{error:#}").contains("c.svg"), "{error:#}");
        let all = [series("case", true, "f32", &[(1.0, Some(1.0))])];
        let error =
            stability("stability", &all, &dir.join("s.svg"), &dir.join("s.png")).unwrap_err();
        assert!(format!("{error:#}").contains("s.svg"), "{error:#}");
        let _ = std::fs::remove_dir_all(&base);
    }

    #[test]
    fn log_axis_holds_a_decade_and_labels_round_values() {
        let axis = LogAxis::new(2_000.0, 8_000.0);
        assert!(axis.lo <= 1_000.0 && axis.hi >= 10_000.0);
        assert_eq!(axis.label(2_000.000_000_1), "2k");
        assert_eq!(axis.label(3_000.0), "");
        assert_eq!(compact(1e-6), "1e-6");
        assert_eq!(compact(0.25), "0.25");
        assert_eq!(compact(150.0), "150");
    }
}
