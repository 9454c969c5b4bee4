//! Small SVG figures (no plotting dependency): histograms, nested boxes in 2-D projections, and a
//! series on a log scale — the paper's Figs. 3, 4 and 5.

use calib_core::Interval;
use std::fmt::Write as _;

const W: f64 = 360.0;
const H: f64 = 280.0;
const M: f64 = 45.0;

fn header(width: f64, title: &str) -> String {
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{}\" font-family=\"sans-serif\" font-size=\"11\">\n\
         <rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n<text x=\"{}\" y=\"16\" text-anchor=\"middle\" font-size=\"13\">{title}</text>\n",
        H + 20.0,
        width / 2.0
    )
}

/// A short axis label: integers as integers, others with 4 significant digits.
fn label(v: f64) -> String {
    if v == v.round() && v.abs() < 1e6 {
        format!("{v:.0}")
    } else {
        let digits = (4 - v.abs().log10().ceil() as i32).clamp(0, 12) as usize;
        format!("{v:.digits$}")
    }
}

/// `[lo, hi]` widened by 5% on each side, so that boxes do not sit on the frame.
fn padded(i: Interval) -> Interval {
    let w = 0.05 * (i.sup() - i.inf());
    Interval::new(i.inf() - w, i.sup() + w)
}

/// Maps `[lo, hi]` to `[a, b]` pixels.
fn scale(v: f64, lo: f64, hi: f64, a: f64, b: f64) -> f64 {
    if hi > lo {
        a + (v - lo) / (hi - lo) * (b - a)
    } else {
        0.5 * (a + b)
    }
}

fn axes(s: &mut String, x0: f64, xlabel: &str, ylabel: &str, xr: (f64, f64), yr: (f64, f64)) {
    let (l, r, t, b) = (x0 + M, x0 + W - 10.0, 30.0, H - 10.0);
    let _ = writeln!(
        s,
        "<rect x=\"{l}\" y=\"{t}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"black\"/>",
        r - l,
        b - t
    );
    let _ = writeln!(
        s,
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{xlabel}</text>",
        (l + r) / 2.0,
        H + 12.0
    );
    let _ = writeln!(s, "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" transform=\"rotate(-90 {} {})\">{ylabel}</text>", x0 + 12.0, (t + b) / 2.0, x0 + 12.0, (t + b) / 2.0);
    for (v, x, anchor) in [(xr.0, l, "start"), (xr.1, r, "end")] {
        let _ = writeln!(
            s,
            "<text x=\"{x}\" y=\"{}\" text-anchor=\"{anchor}\">{}</text>",
            b + 12.0,
            label(v)
        );
    }
    for (v, y) in [(yr.0, b), (yr.1, t)] {
        let _ = writeln!(
            s,
            "<text x=\"{}\" y=\"{y}\" text-anchor=\"end\">{}</text>",
            l - 3.0,
            label(v)
        );
    }
}

/// Fig. 3: a histogram of `values` with the certified interval drawn as a band.
pub fn histogram(values: &[f64], certified: Interval, title: &str, xlabel: &str) -> String {
    let lo = values.iter().copied().fold(certified.inf(), f64::min);
    let hi = values.iter().copied().fold(certified.sup(), f64::max);
    let bins = 40;
    let mut counts = vec![0usize; bins];
    for v in values {
        let i = (((v - lo) / (hi - lo).max(f64::MIN_POSITIVE)) * bins as f64) as usize;
        counts[i.min(bins - 1)] += 1;
    }
    let top = counts.iter().copied().max().unwrap_or(1).max(1) as f64;
    let mut s = header(W, title);
    let (l, r, t, b) = (M, W - 10.0, 30.0, H - 10.0);
    let (cl, cr) = (
        scale(certified.inf(), lo, hi, l, r),
        scale(certified.sup(), lo, hi, l, r),
    );
    let _ = writeln!(
        s,
        "<rect x=\"{cl}\" y=\"{t}\" width=\"{}\" height=\"{}\" fill=\"#cde\"/>",
        (cr - cl).max(1.0),
        b - t
    );
    for (i, c) in counts.iter().enumerate() {
        let x = l + i as f64 * (r - l) / bins as f64;
        let h = *c as f64 / top * (b - t);
        let _ = writeln!(
            s,
            "<rect x=\"{x}\" y=\"{}\" width=\"{}\" height=\"{h}\" fill=\"#c33\"/>",
            b - h,
            (r - l) / bins as f64 - 1.0
        );
    }
    axes(&mut s, 0.0, xlabel, "count", (lo, hi), (0.0, top));
    let _ = writeln!(
        s,
        "<text x=\"{}\" y=\"44\" fill=\"#369\">certified interval</text>\n</svg>",
        l + 5.0
    );
    s
}

/// Fig. 4: nested boxes projected on pairs of parameters, one panel per pair.
pub fn nested_boxes(
    boxes: &[(&str, &str, [Interval; 7])],
    pairs: &[(usize, usize)],
    names: &[&str; 7],
    title: &str,
) -> String {
    let width = W * pairs.len() as f64;
    let mut s = header(width, title);
    for (p, &(i, j)) in pairs.iter().enumerate() {
        let x0 = p as f64 * W;
        let hull = |k: usize| {
            padded(
                boxes
                    .iter()
                    .fold(Interval::EMPTY, |h, (_, _, b)| h.hull(b[k])),
            )
        };
        let (hi_, hj) = (hull(i), hull(j));
        let (l, r, t, b) = (x0 + M, x0 + W - 10.0, 30.0, H - 10.0);
        for (name, colour, bx) in boxes {
            if bx[i].is_empty() || bx[j].is_empty() {
                continue;
            }
            let (xa, xb) = (
                scale(bx[i].inf(), hi_.inf(), hi_.sup(), l, r),
                scale(bx[i].sup(), hi_.inf(), hi_.sup(), l, r),
            );
            let (ya, yb) = (
                scale(bx[j].sup(), hj.inf(), hj.sup(), b, t),
                scale(bx[j].inf(), hj.inf(), hj.sup(), b, t),
            );
            let _ = writeln!(s, "<rect x=\"{xa}\" y=\"{ya}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"1.5\"><title>{name}</title></rect>", (xb - xa).max(0.5), (yb - ya).max(0.5));
        }
        axes(
            &mut s,
            x0,
            names[i],
            names[j],
            (hi_.inf(), hi_.sup()),
            (hj.inf(), hj.sup()),
        );
    }
    let legend: Vec<String> = boxes
        .iter()
        .map(|(l, c, _)| format!("<tspan fill=\"{c}\">{l}</tspan>"))
        .collect();
    let _ = writeln!(
        s,
        "<text x=\"{}\" y=\"{}\">{}</text>\n</svg>",
        M,
        H + 18.0,
        legend.join("  ")
    );
    s
}

/// Fig. 5: a positive series on a log scale (total box volume per sweep step).
pub fn log_series(values: &[f64], title: &str, xlabel: &str, ylabel: &str) -> String {
    let positive: Vec<f64> = values.iter().map(|v| v.max(f64::MIN_POSITIVE)).collect();
    let (lo, hi) = positive
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v.log10()), b.max(v.log10()))
        });
    let (lo, hi) = if hi > lo {
        (lo, hi)
    } else {
        (lo - 1.0, hi + 1.0)
    };
    let mut s = header(W, title);
    let (l, r, t, b) = (M, W - 10.0, 30.0, H - 10.0);
    let n = positive.len().max(2) - 1;
    let points: Vec<String> = positive
        .iter()
        .enumerate()
        .map(|(i, v)| {
            format!(
                "{},{}",
                scale(i as f64, 0.0, n as f64, l, r),
                scale(v.log10(), lo, hi, b, t)
            )
        })
        .collect();
    let _ = writeln!(
        s,
        "<polyline points=\"{}\" fill=\"none\" stroke=\"#c33\" stroke-width=\"2\"/>",
        points.join(" ")
    );
    axes(
        &mut s,
        0.0,
        xlabel,
        &format!("log10 {ylabel}"),
        (0.0, n as f64),
        (lo, hi),
    );
    s.push_str("</svg>\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn figures_are_well_formed_svg() {
        let b: [Interval; 7] = core::array::from_fn(|j| Interval::new(j as f64, j as f64 + 1.0));
        for svg in [
            histogram(&[1.0, 1.5, 2.0, 2.0], Interval::new(1.2, 1.8), "t", "x"),
            nested_boxes(
                &[("x0", "black", b)],
                &[(0, 1), (0, 2)],
                &crate::PARAMETER_NAMES,
                "t",
            ),
            log_series(&[1.0, 0.5, 0.25], "t", "step", "volume"),
        ] {
            assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
            assert!(!svg.contains("NaN") && !svg.contains("inf"));
        }
        // The log scale spans the data: first point at the top, last at the bottom of the frame.
        let svg = log_series(&[1e-8, 1e-9], "t", "step", "volume");
        assert!(svg.contains("points=\"45,30 350,270\""), "{svg}");
        assert_eq!(
            (label(8.0), label(-9.0104), label(52.36512)),
            ("8".into(), "-9.010".into(), "52.37".into())
        );
    }
}
