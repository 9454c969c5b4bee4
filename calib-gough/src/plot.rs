//! The figures, drawn by `plotters` into SVG strings: nested boxes in 2-D projections (the paper's
//! Fig. 4), a per-parameter range chart, a histogram against certified bands (Fig. 3) and a series
//! on a log scale (Fig. 5).
//!
//! Every figure has real axes with ticks and labels, and its legend in a strip below the plots, so
//! that it never covers data. The SVG is self-contained (text, lines and rectangles only), so it can
//! be written to a file or inlined in the HTML certificate.

use calib_core::Interval;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

/// A colour, as red, green, blue bytes.
pub type Colour = (u8, u8, u8);

/// The initial box x0.
pub const X0: Colour = (0x30, 0x30, 0x30);
/// The paper's fixed point x1.
pub const X1: Colour = (0x33, 0x66, 0x99);
/// The paper's sweep hull x2.
pub const X2: Colour = (0x44, 0x99, 0x33);
/// The tight certified outer box.
pub const OUTER: Colour = (0x99, 0x33, 0x99);
/// The certified inner bounds.
pub const INNER: Colour = (0xcc, 0x33, 0x33);
/// Least-squares solutions.
pub const LEAST_SQUARES: Colour = (0xe0, 0x80, 0x00);

/// A named, coloured box drawn in a figure.
#[derive(Clone, Debug)]
pub struct Layer {
    /// The legend entry.
    pub label: String,
    /// Its colour.
    pub colour: Colour,
    /// The box (empty components are not drawn).
    pub boxes: [Interval; 7],
    /// Whether the box is shaded (used for the inner bounds) rather than outlined.
    pub filled: bool,
}

impl Layer {
    /// An outlined box.
    pub fn outline(label: &str, colour: Colour, boxes: [Interval; 7]) -> Layer {
        Layer {
            label: label.into(),
            colour,
            boxes,
            filled: false,
        }
    }

    /// A shaded box.
    pub fn shaded(label: &str, colour: Colour, boxes: [Interval; 7]) -> Layer {
        Layer {
            filled: true,
            ..Layer::outline(label, colour, boxes)
        }
    }
}

/// A leg's boxes as layers, widest first: x0, x1, x2 (with a sweep), the outer box (unless it
/// is x1 itself, with `--fast`) and the shaded inner bounds.
pub fn leg_layers(r: &crate::certification::LegResult) -> Vec<Layer> {
    let mut layers = vec![Layer::outline("x0", X0, r.x0)];
    layers.extend(r.x1.map(|b| Layer::outline("x1", X1, b)));
    layers.extend(r.x2.flatten().map(|b| Layer::outline("x2", X2, b)));
    if r.converged.is_some() {
        layers.extend(r.outer.map(|b| Layer::outline("outer", OUTER, b)));
    }
    layers.extend(r.inner.map(|b| Layer::shaded("inner", INNER, b)));
    layers
}

/// The projections of a leg's figures: (ax, ay), (bx, by) and (az, l).
pub const LEG_PROJECTIONS: [(usize, usize); 3] = [(0, 1), (3, 4), (2, 6)];

/// Named, coloured points (parameter vectors) drawn as dots over the boxes.
#[derive(Clone, Copy, Debug)]
pub struct Points<'a> {
    /// The legend entry.
    pub label: &'a str,
    /// Their colour.
    pub colour: Colour,
    /// The parameter vectors.
    pub points: &'a [[f64; 7]],
}

/// A figure could not be drawn (the SVG backend reported an error).
#[derive(Debug, Clone, PartialEq)]
pub struct PlotError(pub String);

impl std::fmt::Display for PlotError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "cannot draw the figure: {}", self.0)
    }
}

impl std::error::Error for PlotError {}

fn failed<E: std::fmt::Display>(e: E) -> PlotError {
    PlotError(e.to_string())
}

#[doc(hidden)]
pub const PANEL: (u32, u32) = (400, 340);
#[doc(hidden)]
pub const TITLE_HEIGHT: u32 = 30;
const FONT: &str = "sans-serif";

fn rgb((r, g, b): Colour) -> RGBColor {
    RGBColor(r, g, b)
}

/// The smallest interval holding every finite value given, widened by 6% on each side so that
/// nothing sits on the frame; a degenerate range is given a small width around its value.
#[doc(hidden)]
pub fn axis_range(values: impl IntoIterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .into_iter()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if lo > hi {
        return (0.0, 1.0);
    }
    let width = if hi > lo {
        hi - lo
    } else {
        (1e-9 * lo.abs()).max(1e-12)
    };
    (lo - 0.06 * width, hi + 0.06 * width)
}

/// Decimals that tell apart ticks over a span: those of the tick step, taken as span / 5 rounded
/// down to 1, 2 or 5 times a power of ten (as plotters places at most 5–6 ticks).
#[doc(hidden)]
pub fn decimals(span: f64) -> usize {
    if !(span > 0.0 && span.is_finite()) {
        return 3;
    }
    let s = span / 5.0;
    let p = 10f64.powf(s.log10().floor());
    let m = s / p;
    let step = p * if m >= 5.0 {
        5.0
    } else if m >= 2.0 {
        2.0
    } else {
        1.0
    };
    (-step.log10() - 1e-9).ceil().clamp(0.0, 12.0) as usize
}

/// A tick label with `digits` decimals; a value that rounds to zero is printed as `0` (not `-0.00`).
fn tick(v: f64, digits: usize, signed: bool) -> String {
    let s = format!("{v:.digits$}");
    if s.chars().all(|c| matches!(c, '-' | '0' | '.')) {
        return "0".into();
    }
    if signed && v > 0.0 {
        format!("+{s}")
    } else {
        s
    }
}

/// The bounds of `v` clamped into `range`, or `None` when `v` is empty or misses it.
fn clamped(v: Interval, (lo, hi): (f64, f64)) -> Option<(f64, f64)> {
    if v.is_empty() || v.sup() < lo || v.inf() > hi {
        return None;
    }
    Some((v.inf().max(lo), v.sup().min(hi)))
}

/// One legend entry: a swatch (outlined, shaded or a dot) and its label.
#[doc(hidden)]
pub struct Entry {
    pub label: String,
    pub colour: Colour,
    pub kind: Swatch,
}

#[derive(Clone, Copy, PartialEq)]
#[doc(hidden)]
pub enum Swatch {
    Outline,
    Shaded,
    Dot,
}

/// Height of one legend row.
const LEGEND_ROW: u32 = 24;

/// The legend laid out in rows that fit `width`: each entry with its row and x position. Text
/// width is estimated at 8 px per character (14 px sans-serif averages less).
#[doc(hidden)]
pub fn legend_layout(entries: &[Entry], width: u32) -> Vec<(u32, i32, &Entry)> {
    let (mut row, mut x) = (0u32, 40i32);
    let mut out = Vec::with_capacity(entries.len());
    for e in entries {
        let w = 24 + 8 * e.label.chars().count() as i32 + 24;
        if x > 40 && x + w > width as i32 {
            row += 1;
            x = 40;
        }
        out.push((row, x, e));
        x += w;
    }
    out
}

/// Draws the legend in `area` (a strip below the plots).
fn legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    layout: &[(u32, i32, &Entry)],
) -> Result<(), PlotError> {
    for &(row, x, e) in layout {
        let y = (row * LEGEND_ROW + LEGEND_ROW / 2 + 4) as i32;
        let c = rgb(e.colour);
        match e.kind {
            Swatch::Outline => area.draw(&Rectangle::new(
                [(x, y - 6), (x + 18, y + 6)],
                c.stroke_width(2),
            )),
            Swatch::Shaded => area.draw(&Rectangle::new(
                [(x, y - 6), (x + 18, y + 6)],
                c.mix(0.3).filled(),
            )),
            Swatch::Dot => area.draw(&Circle::new((x + 9, y), 3, c.mix(0.8).filled())),
        }
        .map_err(failed)?;
        area.draw(&Text::new(
            e.label.clone(),
            (x + 24, y - 7),
            (FONT, 14).into_font().color(&BLACK),
        ))
        .map_err(failed)?;
    }
    Ok(())
}

/// The drawing area of a figure's plots.
type Plots<'a> = DrawingArea<SVGBackend<'a>, plotters::coord::Shift>;

/// A figure `width` wide: the title on top, then `plot_height` for the plots (returned, to draw
/// on), then the legend in as many rows as it needs. Call `present` on the plots when done.
fn frame<'a>(
    buf: &'a mut String,
    width: u32,
    plot_height: u32,
    title: &str,
    entries: &[Entry],
) -> Result<Plots<'a>, PlotError> {
    let layout = legend_layout(entries, width);
    let rows = layout.last().map_or(0, |(row, _, _)| row + 1);
    let height = TITLE_HEIGHT + plot_height + rows * LEGEND_ROW + 10;
    let root = SVGBackend::with_string(buf, (width, height)).into_drawing_area();
    root.fill(&WHITE).map_err(failed)?;
    let (head, rest) = root.split_vertically(TITLE_HEIGHT);
    let (plots, strip) = rest.split_vertically(plot_height);
    head.draw(&Text::new(
        title.to_string(),
        ((width / 2) as i32, 8),
        (FONT, 17)
            .into_font()
            .color(&BLACK)
            .pos(plotters::style::text_anchor::Pos::new(
                plotters::style::text_anchor::HPos::Center,
                plotters::style::text_anchor::VPos::Top,
            )),
    ))
    .map_err(failed)?;
    legend(&strip, &layout)?;
    Ok(plots)
}

/// A chart with labelled axes on `area` over the given ranges.
fn chart<'a, 'b>(
    area: &'b DrawingArea<SVGBackend<'a>, plotters::coord::Shift>,
    x: (f64, f64),
    y: (f64, f64),
) -> Result<ChartContext<'b, SVGBackend<'a>, Cartesian2d<RangedCoordf64, RangedCoordf64>>, PlotError>
{
    let y_digits = decimals(y.1 - y.0);
    let widest = [y.0, y.1]
        .iter()
        .map(|v| format!("{v:.y_digits$}").len())
        .max()
        .unwrap_or(4) as u32;
    ChartBuilder::on(area)
        .margin(8)
        .margin_right(16)
        .x_label_area_size(42)
        .y_label_area_size(24 + 7 * widest)
        .build_cartesian_2d(x.0..x.1, y.0..y.1)
        .map_err(failed)
}

/// The house style of every chart's grid: light lines, label and axis-name fonts.
fn house_style<'m, 'a, 'b, X: Ranged, Y: Ranged, DB: DrawingBackend>(
    mesh: &'m mut plotters::chart::MeshStyle<'a, 'b, X, Y, DB>,
) -> &'m mut plotters::chart::MeshStyle<'a, 'b, X, Y, DB> {
    mesh.light_line_style(RGBColor(0xee, 0xee, 0xee))
        .bold_line_style(RGBColor(0xdd, 0xdd, 0xdd))
        .label_style((FONT, 12))
        .axis_desc_style((FONT, 14))
}

/// Axes, ticks, tick labels and axis names of a chart.
fn axes(
    chart: &mut ChartContext<'_, SVGBackend<'_>, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    x: (f64, f64),
    y: (f64, f64),
    x_name: &str,
    y_name: &str,
) -> Result<(), PlotError> {
    let (xd, yd) = (decimals(x.1 - x.0), decimals(y.1 - y.0));
    let x_fmt = move |v: &f64| tick(*v, xd, false);
    let y_fmt = move |v: &f64| tick(*v, yd, false);
    let mut mesh = chart.configure_mesh();
    house_style(&mut mesh)
        .x_labels(5)
        .y_labels(6)
        .x_label_formatter(&x_fmt)
        .y_label_formatter(&y_fmt)
        .x_desc(x_name)
        .y_desc(y_name)
        .draw()
        .map_err(failed)
}

/// The frame of one projection panel: boxes only, then points within one box-width of the boxes
/// (a diverged fit far away would shrink the boxes to dots).
fn panel_range(layers: &[Layer], dots: &[[f64; 7]], k: usize) -> (f64, f64) {
    if layers.is_empty() {
        return axis_range(dots.iter().map(|p| p[k]));
    }
    let boxes = axis_range(
        layers
            .iter()
            .flat_map(|l| [l.boxes[k].inf(), l.boxes[k].sup()])
            .filter(|v| !v.is_nan()),
    );
    let width = boxes.1 - boxes.0;
    let near = |v: f64| v >= boxes.0 - width && v <= boxes.1 + width;
    axis_range(
        [boxes.0, boxes.1]
            .into_iter()
            .chain(dots.iter().map(|p| p[k]).filter(|v| near(*v))),
    )
}

fn within(v: f64, (lo, hi): (f64, f64)) -> bool {
    lo <= v && v <= hi
}

/// Legend entries of layers: outlined or shaded swatches.
fn layer_entries(layers: &[Layer], all_shaded: bool) -> Vec<Entry> {
    layers
        .iter()
        .map(|l| Entry {
            label: l.label.clone(),
            colour: l.colour,
            kind: if l.filled || all_shaded {
                Swatch::Shaded
            } else {
                Swatch::Outline
            },
        })
        .collect()
}

/// The paper's Fig. 4: boxes projected on pairs of parameters, one panel per pair `(i, j)` (the
/// i-th parameter across, the j-th up), with optional points (least-squares solutions) on top.
/// Points far outside every box are left out of the frames and counted in the legend.
pub fn nested_boxes(
    layers: &[Layer],
    points: Option<Points<'_>>,
    pairs: &[(usize, usize)],
    names: &[&str; 7],
    title: &str,
) -> Result<String, PlotError> {
    let dots = points.map_or(&[][..], |p| p.points);
    let frames: Vec<((f64, f64), (f64, f64))> = pairs
        .iter()
        .map(|&(i, j)| (panel_range(layers, dots, i), panel_range(layers, dots, j)))
        .collect();
    let shown = |v: &[f64; 7]| {
        pairs
            .iter()
            .zip(&frames)
            .all(|(&(i, j), &(xr, yr))| within(v[i], xr) && within(v[j], yr))
    };
    let outside = dots.iter().filter(|v| !shown(v)).count();
    let mut entries = layer_entries(layers, false);
    entries.extend(points.map(|p| Entry {
        label: if outside > 0 {
            format!("{} ({outside} outside the frames)", p.label)
        } else {
            p.label.into()
        },
        colour: p.colour,
        kind: Swatch::Dot,
    }));
    let columns = pairs.len().max(1);
    let mut buf = String::new();
    {
        let plots = frame(&mut buf, PANEL.0 * columns as u32, PANEL.1, title, &entries)?;
        for (panel, (&(i, j), &(xr, yr))) in plots
            .split_evenly((1, columns))
            .iter()
            .zip(pairs.iter().zip(&frames))
        {
            let mut c = chart(panel, xr, yr)?;
            axes(&mut c, xr, yr, names[i], names[j])?;
            for l in layers {
                let (Some((x0, x1)), Some((y0, y1))) =
                    (clamped(l.boxes[i], xr), clamped(l.boxes[j], yr))
                else {
                    continue;
                };
                let colour = rgb(l.colour);
                if l.filled {
                    c.draw_series(std::iter::once(Rectangle::new(
                        [(x0, y0), (x1, y1)],
                        colour.mix(0.25).filled(),
                    )))
                    .map_err(failed)?;
                }
                let width = if l.filled { 1 } else { 2 };
                c.draw_series(std::iter::once(Rectangle::new(
                    [(x0, y0), (x1, y1)],
                    colour.stroke_width(width),
                )))
                .map_err(failed)?;
            }
            if let Some(p) = points {
                let colour = rgb(p.colour).mix(0.5).filled();
                c.draw_series(
                    p.points
                        .iter()
                        .filter(|v| within(v[i], xr) && within(v[j], yr))
                        .map(|v| Circle::new((v[i], v[j]), 2, colour)),
                )
                .map_err(failed)?;
            }
        }
        plots.present().map_err(failed)?;
    }
    Ok(buf)
}

/// Each parameter's range in every layer, as horizontal bars on one axis: the value minus
/// `centre` (the nominal value), so that parameters of different sizes share the scale.
pub fn parameter_ranges(
    layers: &[Layer],
    centre: &[f64; 7],
    names: &[&str; 7],
    title: &str,
) -> Result<String, PlotError> {
    let xr = axis_range(layers.iter().flat_map(|l| {
        (0..7).flat_map(move |j| [l.boxes[j].inf() - centre[j], l.boxes[j].sup() - centre[j]])
    }));
    let xd = decimals(xr.1 - xr.0);
    let x_fmt = move |v: &f64| tick(*v, xd, true);
    let name_of = |v: &f64| {
        let k = v.round();
        if (v - k).abs() < 1e-6 && (0.0..7.0).contains(&k) {
            names[6 - k as usize].to_string()
        } else {
            String::new()
        }
    };
    let mut buf = String::new();
    {
        let plots = frame(&mut buf, 820, 360, title, &layer_entries(layers, true))?;
        let mut c = ChartBuilder::on(&plots)
            .margin(8)
            .margin_right(20)
            .x_label_area_size(42)
            .y_label_area_size(48)
            .build_cartesian_2d(xr.0..xr.1, -0.6f64..6.6f64)
            .map_err(failed)?;
        let mut mesh = c.configure_mesh();
        house_style(&mut mesh)
            .x_labels(7)
            .y_labels(15)
            .x_label_formatter(&x_fmt)
            .y_label_formatter(&name_of)
            .disable_y_mesh()
            .x_desc("value − nominal (cm)")
            .draw()
            .map_err(failed)?;
        let band = 0.8 / layers.len().max(1) as f64;
        for (k, l) in layers.iter().enumerate() {
            let colour = rgb(l.colour).mix(if k == 0 { 0.3 } else { 0.7 });
            let bars = (0..7).filter_map(|j| {
                let (lo, hi) = clamped(l.boxes[j] - Interval::point(centre[j]), xr)?;
                let y = (6 - j) as f64 + 0.4 - band * (k as f64 + 0.5);
                Some(Rectangle::new(
                    [(lo, y - 0.4 * band), (hi, y + 0.4 * band)],
                    colour.filled(),
                ))
            });
            c.draw_series(bars).map_err(failed)?;
        }
        c.draw_series(LineSeries::new(
            [(0.0, -0.6), (0.0, 6.6)],
            BLACK.mix(0.5).stroke_width(1),
        ))
        .map_err(failed)?;
        plots.present().map_err(failed)?;
    }
    Ok(buf)
}

/// The paper's Fig. 3: a histogram of `values` with intervals (x0, the certified boxes) drawn as
/// shaded bands behind it.
pub fn histogram(
    values: &[f64],
    bands: &[(&str, Colour, Interval)],
    title: &str,
    x_name: &str,
) -> Result<String, PlotError> {
    let finite: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    let xr = axis_range(
        finite
            .iter()
            .copied()
            .chain(bands.iter().flat_map(|(_, _, b)| [b.inf(), b.sup()])),
    );
    let bins = 40;
    let step = (xr.1 - xr.0) / bins as f64;
    let mut counts = vec![0usize; bins];
    for v in &finite {
        let i = ((v - xr.0) / step) as usize;
        counts[i.min(bins - 1)] += 1;
    }
    let top = counts.iter().copied().max().unwrap_or(0).max(1) as f64 * 1.1;
    let mut entries: Vec<Entry> = bands
        .iter()
        .map(|(label, colour, _)| Entry {
            label: label.to_string(),
            colour: *colour,
            kind: Swatch::Shaded,
        })
        .collect();
    entries.push(Entry {
        label: format!("least squares ({})", finite.len()),
        colour: LEAST_SQUARES,
        kind: Swatch::Shaded,
    });
    let mut buf = String::new();
    {
        let plots = frame(&mut buf, PANEL.0 + 260, PANEL.1, title, &entries)?;
        let yr = (0.0, top);
        let mut c = chart(&plots, xr, yr)?;
        axes(&mut c, xr, yr, x_name, "count")?;
        for (_, colour, b) in bands {
            if let Some((lo, hi)) = clamped(*b, xr) {
                c.draw_series(std::iter::once(Rectangle::new(
                    [(lo, 0.0), (hi, top)],
                    rgb(*colour).mix(0.18).filled(),
                )))
                .map_err(failed)?;
            }
        }
        c.draw_series(
            counts
                .iter()
                .enumerate()
                .filter(|(_, n)| **n > 0)
                .map(|(i, n)| {
                    let x = xr.0 + i as f64 * step;
                    Rectangle::new(
                        [(x + 0.05 * step, 0.0), (x + 0.95 * step, *n as f64)],
                        rgb(LEAST_SQUARES).filled(),
                    )
                }),
        )
        .map_err(failed)?;
        plots.present().map_err(failed)?;
    }
    Ok(buf)
}

/// The paper's Fig. 5: a positive series on a log scale (the total box volume per sweep step).
pub fn log_series(
    values: &[f64],
    title: &str,
    x_name: &str,
    y_name: &str,
) -> Result<String, PlotError> {
    let positive: Vec<(f64, f64)> = values
        .iter()
        .enumerate()
        .filter(|(_, v)| **v > 0.0 && v.is_finite())
        .map(|(i, v)| (i as f64, *v))
        .collect();
    let (lo, hi) = positive
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), (_, v)| {
            (lo.min(*v), hi.max(*v))
        });
    let (lo, hi) = if lo <= hi {
        (lo / 1.5, hi * 1.5)
    } else {
        (1e-3, 1.0)
    };
    let n = values.len().max(2) as f64 - 1.0;
    let entries = [Entry {
        label: y_name.into(),
        colour: X1,
        kind: Swatch::Dot,
    }];
    let mut buf = String::new();
    {
        let plots = frame(&mut buf, PANEL.0 + 160, PANEL.1, title, &entries)?;
        let mut c = ChartBuilder::on(&plots)
            .margin(8)
            .margin_right(16)
            .x_label_area_size(42)
            .y_label_area_size(70)
            .build_cartesian_2d(-0.2..n + 0.2, (lo..hi).log_scale())
            .map_err(failed)?;
        let x_fmt = |v: &f64| tick(*v, 0, false);
        let y_fmt = |v: &f64| format!("{v:.0e}");
        let mut mesh = c.configure_mesh();
        house_style(&mut mesh)
            .x_labels(values.len().clamp(2, 12))
            .y_labels(6)
            .max_light_lines(2)
            .x_label_formatter(&x_fmt)
            .y_label_formatter(&y_fmt)
            .x_desc(x_name)
            .y_desc(y_name)
            .draw()
            .map_err(failed)?;
        let colour = rgb(X1);
        c.draw_series(LineSeries::new(
            positive.iter().copied(),
            colour.stroke_width(2),
        ))
        .map_err(failed)?;
        c.draw_series(positive.iter().map(|&p| Circle::new(p, 3, colour.filled())))
            .map_err(failed)?;
        plots.present().map_err(failed)?;
    }
    Ok(buf)
}

/// A heat map per slab (side by side): each cell coloured by its value on one scale from pale
/// (0) to dark red (the largest value of all cells), the scale's ends and the smallest value in
/// the legend — from 0, so that cells whose bounds differ by a few percent look alike (a scale
/// from the smallest value would paint 0.0404 and 0.0406 as far apart as 0 and the largest);
/// cells without a value (0: no pose of the workspace) white.
pub fn heat_maps(
    slabs: &[crate::accuracy::MapSlab],
    title: &str,
    unit: &str,
) -> Result<String, PlotError> {
    let values: Vec<f64> = slabs
        .iter()
        .flat_map(|s| s.upper.iter().flatten())
        .copied()
        .filter(|v| v.is_finite() && *v > 0.0)
        .collect();
    let max = values.iter().copied().fold(0.0, f64::max);
    let min = values.iter().copied().fold(max, f64::min);
    const LOW: Colour = (0xfd, 0xe0, 0xc0);
    const HIGH: Colour = (0x99, 0x11, 0x11);
    let shade = |v: f64| -> Colour {
        let t = (v / max).clamp(0.0, 1.0);
        let mix = |a: u8, b: u8| (a as f64 + (b as f64 - a as f64) * t).round() as u8;
        (mix(LOW.0, HIGH.0), mix(LOW.1, HIGH.1), mix(LOW.2, HIGH.2))
    };
    let colour = |v: f64| -> RGBColor {
        if v.is_nan() || v <= 0.0 {
            return WHITE;
        }
        let (r, g, b) = shade(v);
        RGBColor(r, g, b)
    };
    let entries = [
        Entry {
            label: format!("0 {unit}"),
            colour: LOW,
            kind: Swatch::Shaded,
        },
        Entry {
            label: format!("{min:.4} {unit} (smallest bound)"),
            colour: shade(min),
            kind: Swatch::Shaded,
        },
        Entry {
            label: format!("{max:.4} {unit} (largest bound)"),
            colour: HIGH,
            kind: Swatch::Shaded,
        },
    ];
    let panels = slabs.len().max(1) as u32;
    let mut buf = String::new();
    {
        let plots = frame(&mut buf, PANEL.0 * panels.min(3), PANEL.1, title, &entries)?;
        let areas = plots.split_evenly((1, slabs.len().max(1)));
        for (slab, area) in slabs.iter().zip(&areas) {
            let x = (slab.x_edges[0], *slab.x_edges.last().unwrap_or(&1.0));
            let y = (slab.y_edges[0], *slab.y_edges.last().unwrap_or(&1.0));
            let mut c = chart(area, x, y)?;
            axes(
                &mut c,
                x,
                y,
                &format!("x (cm), z in [{:.1}, {:.1}]", slab.z[0], slab.z[1]),
                "y (cm)",
            )?;
            for (ix, column) in slab.upper.iter().enumerate() {
                for (iy, &v) in column.iter().enumerate() {
                    let r = [
                        (slab.x_edges[ix], slab.y_edges[iy]),
                        (slab.x_edges[ix + 1], slab.y_edges[iy + 1]),
                    ];
                    c.draw_series(std::iter::once(Rectangle::new(r, colour(v).filled())))
                        .map_err(failed)?;
                }
            }
        }
        plots.present().map_err(failed)?;
    }
    Ok(buf)
}
