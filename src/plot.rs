//! `hertz plot`: SVG or PNG charts of a run's CSV results (plotters, with an embedded DejaVu Sans
//! font: no system font libraries). Three charts:
//! - contact pressure along the contact surface at one step (`STEM.contact.csv`), with the Hertz
//!   curve p0·√(1 − (s − c)²/a²) when asked;
//! - load–displacement: the summed reaction of each driven boundary condition against its
//!   prescribed value over the steps (`STEM.steps.csv`);
//! - the Newton residual per iteration, one line per step (`STEM.newton.csv`);
//! - a dynamic analysis's energies over time (`STEM.energy.csv`).

use hertz::error::{Error, Result};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::Once;

/// The font every chart is drawn with, compiled into the binary.
const FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");
const FAMILY: &str = "sans-serif";

/// Which chart.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Chart {
    /// Contact pressure along the contact surface
    Pressure,
    /// Reaction against prescribed value over the steps
    Load,
    /// Newton residual per iteration, one line per step
    Residuals,
    /// Energies of a dynamic analysis over time
    Energy,
}

/// Coordinate along the contact surface for the pressure chart.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Along {
    X,
    Y,
    Z,
    /// Distance from the axis of an axisymmetric 3D contact: the coordinate that varies least
    /// over the contact nodes is the axis's direction; r is measured in the other two from
    /// (c, 0)
    R,
}

/// `hertz plot`: arguments.
#[derive(Debug, clap::Args)]
pub struct PlotArgs {
    /// A run's output: any of its files (STEM.out, STEM.contact.csv, ...) or STEM itself
    pub run: PathBuf,
    /// Charts to draw (default: every chart the run has data for)
    #[arg(short, long, value_enum, value_delimiter = ',')]
    pub chart: Vec<Chart>,
    /// Write PNG instead of SVG
    #[arg(long)]
    pub png: bool,
    /// Output directory (default: next to the run's files)
    #[arg(short, long, value_name = "DIR")]
    pub output: Option<PathBuf>,
    /// Step of the pressure chart (default: the last)
    #[arg(long)]
    pub step: Option<usize>,
    /// Load chart over time: each driven boundary condition's reaction against time (force
    /// histories), not against its prescribed value (written as STEM.load_time.svg)
    #[arg(long)]
    pub time: bool,
    /// Coordinate along the contact surface
    #[arg(long, value_enum, default_value = "x")]
    pub along: Along,
    /// Draw the Hertz pressure p0·sqrt(1 − (s − c)²/a²) too: P0,A or P0,A,C
    #[arg(long, value_name = "P0,A[,C]", value_parser = parse_hertz)]
    pub hertz: Option<HertzCurve>,
}

/// The Hertz pressure p0·√(1 − (s − c)²/a²) drawn over the computed one.
#[derive(Debug, Clone, Copy)]
pub struct HertzCurve {
    pub p0: f64,
    pub a: f64,
    /// Centre of the contact along the plotted coordinate.
    pub centre: f64,
}

/// `P0,A` or `P0,A,C`: two or three numbers, p0 and a positive.
fn parse_hertz(s: &str) -> std::result::Result<HertzCurve, String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|w| {
            w.trim()
                .parse::<f64>()
                .map_err(|_| format!("`{w}` is not a number"))
        })
        .collect::<std::result::Result<_, _>>()?;
    match v[..] {
        [p0, a] if p0 > 0.0 && a > 0.0 => Ok(HertzCurve { p0, a, centre: 0.0 }),
        [p0, a, centre] if p0 > 0.0 && a > 0.0 => Ok(HertzCurve { p0, a, centre }),
        _ => Err("expected P0,A or P0,A,C with P0 > 0 and A > 0".into()),
    }
}

/// A CSV file: its header and numeric rows (`nan` and empty cells become NaN).
#[derive(Debug)]
pub struct Table {
    pub columns: Vec<String>,
    pub rows: Vec<Vec<f64>>,
}

impl Table {
    pub fn read(path: &Path) -> Result<Table> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::InputFile {
            file: path.display().to_string(),
            msg: format!("cannot read: {e}"),
        })?;
        let mut lines = text.lines();
        let columns: Vec<String> = lines
            .next()
            .unwrap_or_default()
            .split(',')
            .map(str::to_string)
            .collect();
        let mut rows = Vec::new();
        for (i, l) in lines.enumerate().filter(|(_, l)| !l.trim().is_empty()) {
            let row: Vec<f64> = l
                .split(',')
                .map(|c| c.trim().parse().unwrap_or(f64::NAN))
                .collect();
            if row.len() != columns.len() {
                return Err(Error::InputFile {
                    file: format!("{}:{}", path.display(), i + 2),
                    msg: format!("{} cells for {} columns", row.len(), columns.len()),
                });
            }
            rows.push(row);
        }
        Ok(Table { columns, rows })
    }

    pub fn column(&self, name: &str) -> Option<usize> {
        self.columns.iter().position(|c| c == name)
    }
}

/// One polyline or point series of a chart.
#[derive(Debug, Clone)]
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
    /// Draw markers (data) rather than a line (a closed form).
    pub markers: bool,
}

/// A chart's axes and series.
#[derive(Debug, Clone)]
pub struct Figure {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub log_y: bool,
    /// The x values are whole numbers (iterations): ticks between them are not labelled.
    pub x_integer: bool,
    pub series: Vec<Series>,
}

fn register_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        plotters::style::register_font(FAMILY, FontStyle::Normal, FONT)
            .unwrap_or_else(|_| panic!("the embedded font parses"));
    });
}

/// Ten distinct colours (the first six as before: tests find series by them).
const COLORS: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// Series beyond this many get colours from a blue-to-red ramp (in their order) instead.
const MAX_DISTINCT: usize = COLORS.len();

/// The colour of series `i` of `n`.
fn series_color(i: usize, n: usize) -> RGBColor {
    if n <= MAX_DISTINCT {
        return COLORS[i];
    }
    let t = i as f64 / (n - 1) as f64;
    let lerp = |a: u8, b: u8| (a as f64 + t * (b as f64 - a as f64)).round() as u8;
    let (a, b) = (COLORS[0], COLORS[1]);
    RGBColor(lerp(a.0, b.0), lerp(a.1, b.1), lerp(a.2, b.2))
}

/// The axis range over `values`: padded by 5 %; a field uniform to round-off (a span below 1e-9
/// of its size) gets ±10 % of its value, not an axis over its round-off.
fn range(values: impl Iterator<Item = f64>, log: bool) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && (!log || *v > 0.0))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if !lo.is_finite() {
        return if log { (1e-16, 1.0) } else { (0.0, 1.0) };
    }
    if log {
        return (lo / 2.0, hi * 2.0);
    }
    let size = lo.abs().max(hi.abs());
    let pad = if hi - lo > 1e-9 * size {
        0.05 * (hi - lo)
    } else if size > 0.0 {
        0.1 * size
    } else {
        1.0
    };
    (lo - pad, hi + pad)
}

/// A tick label on a linear axis spanning `span`: the digits the tick spacing needs (about a
/// tenth of the span), in scientific form for very large or small values.
fn linear_label(v: f64, span: f64) -> String {
    let step = (span / 10.0).abs().max(f64::MIN_POSITIVE);
    let mag = v.abs().max(step);
    if !(1e-3..1e6).contains(&mag) {
        let digits = (mag.log10().floor() - step.log10().floor()).clamp(0.0, 6.0) as usize;
        return format!("{v:.digits$e}");
    }
    let decimals = (-step.log10().floor()).clamp(0.0, 9.0) as usize;
    let text = format!("{v:.decimals$}");
    // No "-0" for a tick at zero.
    if text
        .trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        text.trim_start_matches('-').to_string()
    } else {
        text
    }
}

/// A tick label on a log axis: the power of ten it is closest to, or the value in one digit.
fn log_label(v: f64) -> String {
    let e = v.log10();
    if (e - e.round()).abs() < 1e-6 {
        format!("1e{}", e.round() as i64)
    } else {
        format!("{v:.0e}")
    }
}

/// The corner whose quarter of the plot holds the fewest points: the legend goes there.
fn legend_corner(fig: &Figure, x: (f64, f64), y: (f64, f64)) -> SeriesLabelPosition {
    let norm = |v: f64, (a, b): (f64, f64), log: bool| {
        if log {
            (v.ln() - a.ln()) / (b.ln() - a.ln())
        } else {
            (v - a) / (b - a)
        }
    };
    let mut count = [0usize; 4]; // upper right, upper left, lower right, lower left
    for s in &fig.series {
        for &(px, py) in &s.points {
            if !(px.is_finite() && py.is_finite()) || (fig.log_y && py <= 0.0) {
                continue;
            }
            let (u, w) = (norm(px, x, false), norm(py, y, fig.log_y));
            // The legend box spans about 40 % of the width and 35 % of the height.
            let right = u > 0.6;
            let left = u < 0.4;
            let upper = w > 0.65;
            let lower = w < 0.35;
            count[0] += usize::from(right && upper);
            count[1] += usize::from(left && upper);
            count[2] += usize::from(right && lower);
            count[3] += usize::from(left && lower);
        }
    }
    match (0..4).min_by_key(|&i| count[i]).unwrap_or(0) {
        0 => SeriesLabelPosition::UpperRight,
        1 => SeriesLabelPosition::UpperLeft,
        2 => SeriesLabelPosition::LowerRight,
        _ => SeriesLabelPosition::LowerLeft,
    }
}

fn draw_on<DB: DrawingBackend>(area: DrawingArea<DB, Shift>, fig: &Figure) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let fail = |e: &dyn std::fmt::Display| Error::Output(format!("plot `{}`: {e}", fig.title));
    area.fill(&WHITE).map_err(|e| fail(&e))?;
    let all = || fig.series.iter().flat_map(|s| s.points.iter());
    let (x0, x1) = range(all().map(|p| p.0), false);
    let (y0, y1) = range(all().map(|p| p.1), fig.log_y);
    let corner = legend_corner(fig, (x0, x1), (y0, y1));
    let mut builder = ChartBuilder::on(&area);
    builder
        .caption(&fig.title, (FAMILY, 22))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(75);
    let x_fmt = |v: &f64| {
        if fig.x_integer && (v - v.round()).abs() > 1e-9 {
            String::new()
        } else if fig.x_integer {
            format!("{}", v.round() as i64)
        } else {
            linear_label(*v, x1 - x0)
        }
    };
    let y_lin = |v: &f64| linear_label(*v, y1 - y0);
    let y_log = |v: &f64| log_label(*v);
    let n = fig.series.len();
    macro_rules! body {
        ($chart:expr, $y_fmt:expr) => {{
            let mut chart = $chart;
            chart
                .configure_mesh()
                .x_desc(fig.x_label.as_str())
                .y_desc(fig.y_label.as_str())
                .x_label_formatter(&x_fmt)
                .y_label_formatter($y_fmt)
                .label_style((FAMILY, 14))
                .draw()
                .map_err(|e| fail(&e))?;
            for (i, s) in fig.series.iter().enumerate() {
                let color = series_color(i, n);
                let pts: Vec<(f64, f64)> = s
                    .points
                    .iter()
                    .copied()
                    .filter(|p| p.0.is_finite() && p.1.is_finite() && (!fig.log_y || p.1 > 0.0))
                    .collect();
                let anno = if s.markers {
                    chart
                        .draw_series(pts.iter().map(|&p| Circle::new(p, 3, color.filled())))
                        .map_err(|e| fail(&e))?
                } else {
                    chart
                        .draw_series(LineSeries::new(pts, color.stroke_width(2)))
                        .map_err(|e| fail(&e))?
                };
                if !s.label.is_empty() {
                    let markers = s.markers;
                    anno.label(s.label.as_str()).legend(move |(x, y)| {
                        if markers {
                            Circle::new((x + 9, y), 4, color.filled()).into_dyn()
                        } else {
                            PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2))
                                .into_dyn()
                        }
                    });
                }
            }
            chart
                .configure_series_labels()
                .position(corner)
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .label_font((FAMILY, 14))
                .draw()
                .map_err(|e| fail(&e))?;
        }};
    }
    if fig.log_y {
        body!(
            builder
                .build_cartesian_2d(x0..x1, (y0..y1).log_scale())
                .map_err(|e| fail(&e))?,
            &y_log
        );
    } else {
        body!(
            builder
                .build_cartesian_2d(x0..x1, y0..y1)
                .map_err(|e| fail(&e))?,
            &y_lin
        );
    }
    area.present().map_err(|e| fail(&e))?;
    Ok(())
}

/// Draw `fig` to `path` (SVG, or PNG when the extension is `png`), 900 x 560 pixels.
pub fn draw(fig: &Figure, path: &Path) -> Result<()> {
    register_font();
    let size = (900, 560);
    if path.extension().is_some_and(|e| e == "png") {
        draw_on(BitMapBackend::new(path, size).into_drawing_area(), fig)
    } else {
        draw_on(SVGBackend::new(path, size).into_drawing_area(), fig)
    }
}

fn need(t: &Table, path: &Path, name: &str) -> Result<usize> {
    t.column(name).ok_or_else(|| Error::InputFile {
        file: path.display().to_string(),
        msg: format!("no column `{name}`: is this a hertz output file?"),
    })
}

/// The pressure chart of `step` (default: the last) from a contact CSV.
pub fn pressure_figure(
    path: &Path,
    step: Option<usize>,
    along: Along,
    hertz: Option<HertzCurve>,
) -> Result<Figure> {
    let t = Table::read(path)?;
    let [cs, cx, cy, cz, cp, cc] = ["step", "x", "y", "z", "pressure", "condition"]
        .map(|c| need(&t, path, c))
        .into_iter()
        .collect::<Result<Vec<_>>>()?[..]
    else {
        unreachable!("six columns")
    };
    let last = t.rows.iter().map(|r| r[cs] as usize).max().unwrap_or(0);
    let step = step.unwrap_or(last);
    if !t.rows.iter().any(|r| r[cs] as usize == step) {
        return Err(Error::InputFile {
            file: path.display().to_string(),
            msg: format!("no contact results for step {step} (steps 1..{last})"),
        });
    }
    let centre = hertz.map_or(0.0, |h| h.centre);
    // For r: the two in-plane coordinates, the axis's being the one of least range.
    let in_plane = {
        let range = |c: usize| {
            let v = t
                .rows
                .iter()
                .filter(|r| r[cs] as usize == step)
                .map(|r| r[c]);
            v.clone().fold(f64::NEG_INFINITY, f64::max) - v.fold(f64::INFINITY, f64::min)
        };
        let axis = [cx, cy, cz]
            .into_iter()
            .min_by(|&a, &b| range(a).total_cmp(&range(b)))
            .expect("three coordinates");
        let mut rest = [cx, cy, cz].into_iter().filter(|&c| c != axis);
        [rest.next().expect("two"), rest.next().expect("two")]
    };
    let coordinate = |r: &[f64]| match along {
        Along::X => r[cx],
        Along::Y => r[cy],
        Along::Z => r[cz],
        Along::R => (r[in_plane[0]] - centre).hypot(r[in_plane[1]]),
    };
    let mut conditions: Vec<usize> = t.rows.iter().map(|r| r[cc] as usize).collect();
    conditions.sort_unstable();
    conditions.dedup();
    let mut series = Vec::new();
    for c in conditions {
        let mut pts: Vec<(f64, f64)> = t
            .rows
            .iter()
            .filter(|r| r[cs] as usize == step && r[cc] as usize == c && r[cp].is_finite())
            .map(|r| (coordinate(r), r[cp]))
            .collect();
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        series.push(Series {
            label: format!("hertz, contact condition {c}"),
            points: pts,
            markers: true,
        });
    }
    if let Some(h) = hertz {
        let (p0, a) = (h.p0, h.a);
        let (lo, hi) = series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.0))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                (a.min(x), b.max(x))
            });
        let (lo, hi) = if lo < hi { (lo, hi) } else { (-h.a, h.a) };
        let c = if along == Along::R { 0.0 } else { centre };
        let n = 400;
        let points = (0..=n)
            .map(|i| {
                let s = lo + (hi - lo) * i as f64 / n as f64;
                let q = 1.0 - ((s - c) / a).powi(2);
                (s, if q > 0.0 { p0 * q.sqrt() } else { 0.0 })
            })
            .collect();
        series.push(Series {
            label: format!("Hertz: p0 = {p0}, a = {a}"),
            points,
            markers: false,
        });
    }
    Ok(Figure {
        title: format!("Contact pressure, step {step}"),
        x_label: format!("{:?}", along).to_lowercase(),
        y_label: "pressure".into(),
        log_y: false,
        x_integer: false,
        series,
    })
}

/// The load–displacement chart from a steps CSV: each boundary condition's summed reaction
/// against its prescribed value (or against time, `over_time`: force histories), for those whose
/// value changes; against time if none does.
pub fn load_figure(path: &Path, over_time: bool) -> Result<Figure> {
    let t = Table::read(path)?;
    let ct = need(&t, path, "time")?;
    let mut series = Vec::new();
    let mut by_time = Vec::new();
    for (j, name) in t.columns.iter().enumerate() {
        let Some(rest) = name.strip_suffix(|c: char| c.is_ascii_digit()) else {
            continue;
        };
        let Some((bc, kind)) = rest.rsplit_once('.') else {
            continue;
        };
        if kind != "r" {
            continue;
        }
        let dof = &name[name.len() - 1..];
        let Some(ju) = t.column(&format!("{bc}.u{dof}")) else {
            continue;
        };
        let driven = t.rows.iter().any(|r| r[ju] != 0.0);
        let along = if over_time { ct } else { ju };
        let pts: Vec<(f64, f64)> = t.rows.iter().map(|r| (r[along], r[j])).collect();
        let label = format!("{bc}, DOF {dof}");
        if driven {
            series.push(Series {
                label,
                points: std::iter::once((0.0, 0.0)).chain(pts).collect(),
                markers: false,
            });
        } else if t.rows.iter().any(|r| r[j] != 0.0) {
            by_time.push(Series {
                label: format!("{label} (supports)"),
                points: t.rows.iter().map(|r| (r[ct], r[j])).collect(),
                markers: false,
            });
        }
    }
    let (x_label, series) = if series.is_empty() {
        ("time", by_time)
    } else if over_time {
        ("time", series)
    } else {
        ("prescribed displacement (mean over the set)", series)
    };
    Ok(Figure {
        title: "Reaction force".into(),
        x_label: x_label.into(),
        y_label: "summed reaction".into(),
        log_y: false,
        x_integer: false,
        series,
    })
}

/// The Newton residual chart from a Newton CSV: one line per step, log scale.
pub fn residual_figure(path: &Path) -> Result<Figure> {
    let t = Table::read(path)?;
    let (cs, ci, cr) = (
        need(&t, path, "step")?,
        need(&t, path, "iteration")?,
        need(&t, path, "residual")?,
    );
    let mut series: Vec<Series> = Vec::new();
    for r in &t.rows {
        let label = format!("step {}", r[cs]);
        match series.last_mut() {
            Some(s) if s.label == label => s.points.push((r[ci], r[cr])),
            _ => series.push(Series {
                label,
                points: vec![(r[ci], r[cr])],
                markers: false,
            }),
        }
    }
    // Many steps: their colours run from blue (the first) to red (the last), and the legend
    // names about eight of them, the first and the last among them, each in its own colour.
    let n = series.len();
    if n > MAX_DISTINCT {
        let every = n.div_ceil(8);
        for (i, s) in series.iter_mut().enumerate() {
            if i % every != 0 && i != n - 1 {
                s.label.clear();
            }
        }
    }
    Ok(Figure {
        title: "Newton residual per iteration".into(),
        x_label: "iteration".into(),
        y_label: "relative residual".into(),
        log_y: true,
        x_integer: true,
        series,
    })
}

/// The energy chart from an energy CSV: kinetic, internal, contact and damping energies, the
/// external and supports' work, and their balance (what the time scheme created or lost) over
/// time; the columns that stay zero are left out.
pub fn energy_figure(path: &Path) -> Result<Figure> {
    let t = Table::read(path)?;
    let ct = need(&t, path, "time")?;
    let mut series = Vec::new();
    for name in [
        "kinetic", "internal", "contact", "damping", "external", "supports", "balance",
    ] {
        let j = need(&t, path, name)?;
        if name != "balance" && t.rows.iter().all(|r| r[j] == 0.0) {
            continue;
        }
        series.push(Series {
            label: name.into(),
            points: t.rows.iter().map(|r| (r[ct], r[j])).collect(),
            markers: false,
        });
    }
    Ok(Figure {
        title: "Energies".into(),
        x_label: "time".into(),
        y_label: "energy (work since the start)".into(),
        log_y: false,
        x_integer: false,
        series,
    })
}

/// The stem of a run from any of its files (`out/run.contact.csv` -> `out/run`).
fn stem_of(run: &Path) -> PathBuf {
    let name = run.file_name().and_then(|n| n.to_str()).unwrap_or("");
    for suffix in [
        ".contact.csv",
        ".steps.csv",
        ".newton.csv",
        ".energy.csv",
        ".out",
        ".pvd",
    ] {
        if let Some(stem) = name.strip_suffix(suffix) {
            return run.with_file_name(stem);
        }
    }
    run.to_path_buf()
}

/// `hertz plot`: draw the asked (or every available) chart; returns the files written.
pub fn plot_files(args: &PlotArgs) -> Result<Vec<PathBuf>> {
    let stem = stem_of(&args.run);
    let base = stem.file_name().and_then(|n| n.to_str()).unwrap_or("hertz");
    let dir = args
        .output
        .clone()
        .unwrap_or_else(|| stem.parent().map(Path::to_path_buf).unwrap_or_default());
    let input = |ext: &str| stem.with_file_name(format!("{base}.{ext}"));
    let charts: Vec<Chart> = if args.chart.is_empty() {
        [
            (Chart::Pressure, "contact.csv"),
            (Chart::Load, "steps.csv"),
            (Chart::Residuals, "newton.csv"),
            (Chart::Energy, "energy.csv"),
        ]
        .into_iter()
        .filter(|(_, ext)| input(ext).is_file())
        .map(|(c, _)| c)
        .collect()
    } else {
        args.chart.clone()
    };
    if charts.is_empty() {
        return Err(Error::InputFile {
            file: stem.display().to_string(),
            msg: "no results to plot: expected STEM.contact.csv, STEM.steps.csv or \
                  STEM.newton.csv (written by `hertz run`)"
                .into(),
        });
    }
    std::fs::create_dir_all(&dir)
        .map_err(|e| Error::Output(format!("cannot create {}: {e}", dir.display())))?;
    let ext = if args.png { "png" } else { "svg" };
    let mut written = Vec::new();
    for c in charts {
        let (fig, name) = match c {
            Chart::Pressure => (
                pressure_figure(&input("contact.csv"), args.step, args.along, args.hertz)?,
                "pressure",
            ),
            Chart::Load if args.time => (load_figure(&input("steps.csv"), true)?, "load_time"),
            Chart::Load => (load_figure(&input("steps.csv"), false)?, "load"),
            Chart::Residuals => (residual_figure(&input("newton.csv"))?, "residuals"),
            Chart::Energy => (energy_figure(&input("energy.csv"))?, "energy"),
        };
        let out = dir.join(format!("{base}.{name}.{ext}"));
        draw(&fig, &out)?;
        written.push(out);
    }
    Ok(written)
}

#[cfg(test)]
mod tests {
    /// The energy chart draws the energies that are not zero throughout, and the balance always
    /// (the scheme's error, zero when it keeps the energy).
    #[test]
    fn energy_chart_shows_what_moves_and_the_balance() {
        let dir = std::env::temp_dir().join(format!("hertz-plot-e-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("run.energy.csv");
        let csv = format!(
            "{}\n1,0.1,0.4,0.1,0,0,0,0,0\n2,0.2,0.3,0.2,0,0,0,0,1e-17\n",
            hertz::output::outfile::ENERGY_CSV_HEADER
        );
        std::fs::write(&path, csv).unwrap();
        let fig = super::energy_figure(&path).unwrap();
        let labels: Vec<&str> = fig.series.iter().map(|s| s.label.as_str()).collect();
        assert_eq!(labels, ["kinetic", "internal", "balance"]);
        assert_eq!(fig.series[1].points, [(0.1, 0.1), (0.2, 0.2)]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// `--along r` measures the distance from the axis, whichever coordinate the axis runs
    /// along: the same nodes in the plane z = 1 and in the plane y = 1 give the same radii.
    #[test]
    fn radius_is_measured_in_the_contact_plane() {
        let dir = std::env::temp_dir().join(format!("hertz-plot-r-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let points = [(0.0, 0.0, 9.0), (0.3, 0.4, 7.0), (1.2, 0.5, 3.0)];
        let mut radii = Vec::new();
        for axis in [1, 2] {
            let mut csv = format!("{}\n", hertz::output::outfile::CONTACT_CSV_HEADER);
            for (k, &(u, v, p)) in points.iter().enumerate() {
                let (y, z) = if axis == 2 { (v, 1.0) } else { (1.0, v) };
                csv.push_str(&format!("1,1,{k},{u},{y},{z},0,{p},{p},1,0,0\n"));
            }
            let path = dir.join(format!("axis{axis}.contact.csv"));
            std::fs::write(&path, csv).unwrap();
            let fig = super::pressure_figure(&path, None, super::Along::R, None).unwrap();
            radii.push(fig.series[0].points.clone());
        }
        assert_eq!(radii[0], radii[1]);
        assert_eq!(radii[0], vec![(0.0, 9.0), (0.5, 7.0), (1.3, 3.0)]);
        std::fs::remove_dir_all(dir).ok();
    }

    /// The load chart of a press-then-slide run: each driven reaction against its prescribed
    /// value, or with `over_time` against time (the force histories), from the origin.
    #[test]
    fn load_chart_over_time_holds_the_force_histories() {
        let dir = std::env::temp_dir().join(format!("hertz-plot-t-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("run.steps.csv");
        std::fs::write(
            &path,
            "step,time,iterations,substeps,residual,bc2.u2,bc2.r2,bc3.u1,bc3.r1\n\
             1,0.5,2,1,0,-1,4,0,0.5\n\
             2,1.5,2,1,0,-1,5,2,1.5\n",
        )
        .unwrap();
        let points = |over_time| {
            let fig = super::load_figure(&path, over_time).unwrap();
            let pts: Vec<Vec<(f64, f64)>> = fig.series.iter().map(|s| s.points.clone()).collect();
            (fig.x_label, pts)
        };
        let (label, by_value) = points(false);
        assert!(label.starts_with("prescribed"));
        assert_eq!(by_value[0], vec![(0.0, 0.0), (-1.0, 4.0), (-1.0, 5.0)]);
        assert_eq!(by_value[1], vec![(0.0, 0.0), (0.0, 0.5), (2.0, 1.5)]);
        let (label, by_time) = points(true);
        assert_eq!(label, "time");
        assert_eq!(by_time[0], vec![(0.0, 0.0), (0.5, 4.0), (1.5, 5.0)]);
        assert_eq!(by_time[1], vec![(0.0, 0.0), (0.5, 0.5), (1.5, 1.5)]);
        std::fs::remove_dir_all(dir).ok();
    }

    /// The tick labels of an SVG chart (plotters writes each as a `<text>` element).
    fn svg_texts(fig: &super::Figure, tag: &str) -> Vec<String> {
        let path =
            std::env::temp_dir().join(format!("hertz-plot-{tag}-{}.svg", std::process::id()));
        super::draw(fig, &path).unwrap();
        let svg = std::fs::read_to_string(&path).unwrap();
        std::fs::remove_file(&path).ok();
        svg.split("<text")
            .skip(1)
            .map(|t| {
                let body = &t[t.find('>').unwrap() + 1..];
                body[..body.find("</text>").unwrap()].trim().to_string()
            })
            .collect()
    }

    /// Residuals of 15 steps from 1 to 1e-13: the log axis is labelled in powers of ten (no
    /// `9999999998` or `0000001e-13`), the iteration axis in whole numbers, the legend names
    /// eight steps with the first and the last, and no two steps share a colour.
    #[test]
    fn residual_chart_labels_read_cleanly() {
        let dir = std::env::temp_dir().join(format!("hertz-plot-res-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("run.newton.csv");
        let mut csv = String::from("step,iteration,residual\n");
        for step in 1..=15 {
            for it in 0..=4 {
                csv += &format!("{step},{it},{:e}\n", 10f64.powi(-3 * it - (step % 2)));
            }
        }
        std::fs::write(&path, csv).unwrap();
        let fig = super::residual_figure(&path).unwrap();
        std::fs::remove_dir_all(&dir).ok();
        let texts = svg_texts(&fig, "res");
        let ticks: Vec<&String> = texts.iter().filter(|t| t.parse::<f64>().is_ok()).collect();
        assert!(ticks.len() > 6, "{texts:?}");
        for t in &ticks {
            assert!(
                !t.contains("999") && !t.contains("000") && !t.contains('.'),
                "{texts:?}"
            );
        }
        assert!(texts.iter().any(|t| t == "1e-13"), "{texts:?}");
        assert!(
            texts.iter().any(|t| t == "4"),
            "whole iterations: {texts:?}"
        );
        let legend: Vec<&String> = texts.iter().filter(|t| t.starts_with("step ")).collect();
        assert_eq!(legend.len(), 8, "{legend:?}");
        assert!(
            legend.contains(&&"step 1".to_string()) && legend.contains(&&"step 15".to_string())
        );
        let colors: std::collections::HashSet<_> = (0..15)
            .map(|i| super::series_color(i, 15))
            .map(|c| (c.0, c.1, c.2))
            .collect();
        assert_eq!(colors.len(), 15);
    }

    /// A uniform field is drawn on an axis around its value, not over its round-off: its tick
    /// labels differ from each other.
    #[test]
    fn a_uniform_field_gets_a_readable_axis() {
        let points: Vec<(f64, f64)> = (0..9)
            .map(|i| (i as f64 * 0.1, 2.0647 + 1e-15 * (i % 3) as f64))
            .collect();
        let fig = super::Figure {
            title: "uniform".into(),
            x_label: "x".into(),
            y_label: "pressure".into(),
            log_y: false,
            x_integer: false,
            series: vec![super::Series {
                label: "p".into(),
                points,
                markers: true,
            }],
        };
        let texts = svg_texts(&fig, "uniform");
        let ticks: Vec<f64> = texts
            .iter()
            .filter_map(|t| t.parse::<f64>().ok())
            .filter(|v| *v > 1.5)
            .collect();
        assert!(ticks.len() >= 3, "{texts:?}");
        let mut distinct = ticks.clone();
        distinct.dedup();
        assert_eq!(distinct.len(), ticks.len(), "{texts:?}");
    }

    /// The legend goes to the corner with the fewest points: not over data in the upper right.
    #[test]
    fn the_legend_avoids_the_data() {
        let points: Vec<(f64, f64)> = (0..20).map(|i| (0.8 + 0.01 * i as f64, 0.9)).collect();
        let fig = super::Figure {
            title: "t".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            log_y: false,
            x_integer: false,
            series: vec![super::Series {
                label: "a".into(),
                points: [vec![(0.0, 0.0)], points].concat(),
                markers: true,
            }],
        };
        let corner = super::legend_corner(&fig, (0.0, 1.0), (0.0, 1.0));
        assert!(!matches!(
            corner,
            plotters::chart::SeriesLabelPosition::UpperRight
        ));
        assert!(!matches!(
            corner,
            plotters::chart::SeriesLabelPosition::LowerLeft
        ));
    }
}
