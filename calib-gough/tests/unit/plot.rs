//! The tests of `calib_gough::plot`.

use calib_core::Interval;
use calib_gough::plot::*;

fn boxes(shift: f64) -> [Interval; 7] {
    core::array::from_fn(|j| Interval::new(j as f64 + shift, j as f64 + 1.0 - shift))
}

fn well_formed(svg: &str) -> roxmltree::Document<'_> {
    let doc = roxmltree::Document::parse(svg).unwrap_or_else(|e| panic!("{e}\n{svg}"));
    assert_eq!(doc.root_element().tag_name().name(), "svg");
    assert!(!svg.contains("NaN") && !svg.contains("inf"), "{svg}");
    doc
}

fn texts(doc: &roxmltree::Document<'_>) -> Vec<String> {
    doc.descendants()
        .filter(|n| n.has_tag_name("text"))
        .filter_map(|n| n.text().map(|t| t.trim().to_string()))
        .collect()
}

#[test]
fn nested_boxes_have_axes_ticks_and_a_legend() {
    let layers = [
        Layer::outline("x0", X0, boxes(0.0)),
        Layer::shaded("inner", INNER, boxes(0.3)),
    ];
    let near = |d: f64| core::array::from_fn(|j| j as f64 + d);
    // Two points inside the boxes and one far away (a diverged fit) that must not squash
    // the frames: it is left out and counted in the legend.
    let dots: [[f64; 7]; 3] = [near(0.5), near(0.6), [1e3; 7]];
    let svg = nested_boxes(
        &layers,
        Some(Points {
            label: "least squares",
            colour: LEAST_SQUARES,
            points: &dots,
        }),
        &[(0, 1), (3, 4)],
        &calib_gough::PARAMETER_NAMES,
        "leg 1",
    )
    .unwrap();
    let doc = well_formed(&svg);
    let t = texts(&doc);
    for want in [
        "leg 1",
        "ax",
        "ay",
        "bx",
        "by",
        "x0",
        "inner",
        "least squares (1 outside the frames)",
    ] {
        assert!(t.iter().any(|s| s == want), "{want} missing from {t:?}");
    }
    // Ticks: more numeric labels than the two ends of each axis.
    let numbers = t.iter().filter(|s| s.parse::<f64>().is_ok()).count();
    assert!(numbers >= 4 * 4, "{t:?}");
    // Two circles per panel for the two points near the boxes, one in the legend.
    assert_eq!(
        doc.descendants()
            .filter(|n| n.has_tag_name("circle"))
            .count(),
        2 * 2 + 1
    );
}

#[test]
fn the_legend_lies_below_every_plot() {
    let svg = nested_boxes(
        &[Layer::outline("x0", X0, boxes(0.0))],
        None,
        &[(0, 1)],
        &calib_gough::PARAMETER_NAMES,
        "t",
    )
    .unwrap();
    let doc = well_formed(&svg);
    let label = doc
        .descendants()
        .find(|n| n.has_tag_name("text") && n.text().map(str::trim) == Some("x0"))
        .expect("legend entry");
    let y: f64 = label.attribute("y").and_then(|v| v.parse().ok()).unwrap();
    assert!(y > (PANEL.1 + TITLE_HEIGHT) as f64, "legend at y = {y}");
}

#[test]
fn a_long_legend_wraps_into_rows_within_the_figure() {
    let entries: Vec<Entry> = (0..6)
        .map(|k| Entry {
            label: format!("a rather long legend entry number {k}"),
            colour: X0,
            kind: Swatch::Outline,
        })
        .collect();
    let layout = legend_layout(&entries, 600);
    assert!(
        layout.last().unwrap().0 >= 2,
        "rows: {}",
        layout.last().unwrap().0
    );
    for (_, x, e) in &layout {
        let right = x + 24 + 8 * e.label.chars().count() as i32;
        assert!(right <= 600, "{} ends at {right}", e.label);
    }
}

#[test]
fn other_figures_are_well_formed() {
    let t = boxes(0.0);
    for svg in [
        parameter_ranges(
            &[
                Layer::outline("x0", X0, t),
                Layer::shaded("inner", INNER, boxes(0.4)),
            ],
            &t.map(|v| v.mid()),
            &calib_gough::PARAMETER_NAMES,
            "ranges",
        ),
        histogram(
            &[1.0, 1.5, 2.0, 2.0, f64::NAN],
            &[("x1", X1, Interval::new(1.2, 1.8))],
            "t",
            "l (cm)",
        ),
        log_series(&[1.0, 0.5, 0.25, 0.0], "t", "step", "volume"),
        log_series(&[], "t", "step", "volume"),
        nested_boxes(
            &[],
            None,
            &[(0, 1)],
            &calib_gough::PARAMETER_NAMES,
            "nothing",
        ),
    ] {
        let svg = svg.unwrap();
        well_formed(&svg);
    }
}

#[test]
fn tick_labels_tell_ticks_apart() {
    assert_eq!(decimals(0.2), 2);
    assert_eq!(decimals(0.04), 3);
    assert_eq!(decimals(20.0), 0);
    assert_eq!(decimals(2e-9), 10);
    // A degenerate range still gets a positive width around its value.
    let (lo, hi) = axis_range([52.3, 52.3]);
    assert!(lo < 52.3 && 52.3 < hi);
    assert_eq!(axis_range([f64::NAN]), (0.0, 1.0));
}

/// Cells are coloured from 0, not from the smallest value: two nearly equal bounds look
/// nearly alike, a cell without a pose is white, the largest is dark red, and the legend
/// names 0, the smallest and the largest bound.
#[test]
fn heat_maps_colour_from_zero() {
    let slab = calib_gough::accuracy::MapSlab {
        z: [59.0, 61.0],
        x_edges: vec![0.0, 1.0, 2.0],
        y_edges: vec![0.0, 1.0, 2.0],
        upper: vec![vec![0.0, 0.0404], vec![0.0406, 0.0203]],
    };
    let svg = heat_maps(std::slice::from_ref(&slab), "a map", "cm").expect("drawn");
    let doc = well_formed(&svg);
    let fills: Vec<String> = doc
        .descendants()
        .filter(|n| n.has_tag_name("rect"))
        .filter_map(|n| n.attribute("fill").map(|f| f.to_ascii_lowercase()))
        .collect();
    // The largest: dark red; 0.0404 within a shade of it; half of it halfway from pale.
    assert!(fills.contains(&"#991111".to_string()), "{fills:?}");
    assert!(fills.contains(&"#991212".to_string()), "{fills:?}");
    assert!(fills.contains(&"#cb7969".to_string()), "{fills:?}");
    let t = texts(&doc);
    for label in [
        "0 cm",
        "0.0203 cm (smallest bound)",
        "0.0406 cm (largest bound)",
    ] {
        assert!(t.iter().any(|s| s == label), "{label} not in {t:?}");
    }
}
