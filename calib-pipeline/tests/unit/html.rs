//! The tests of `calib_pipeline::html`.

use calib_core::Interval;
use calib_pipeline::html::*;

#[test]
fn sha256_matches_known_digests() {
    assert_eq!(
        sha256_hex(b""),
        "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855"
    );
    assert_eq!(
        sha256_hex(b"abc"),
        "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
    );
}

#[test]
fn printed_bounds_keep_their_meaning() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand::rngs::StdRng::seed_from_u64(11);
    for _ in 0..20_000 {
        let lo: f64 = rng.random_range(-100.0..100.0);
        let hi = lo + rng.random_range(0.0..0.01) * rng.random_range(0.0..1.0f64).powi(4);
        let v = Interval::new(lo, hi);
        let parse = |s: &str| -> (f64, f64) {
            let inner = s.trim_start_matches('[').trim_end_matches(']');
            let (a, b) = inner.split_once(", ").unwrap();
            (a.parse().unwrap(), b.parse().unwrap())
        };
        let (a, b) = parse(&outward(v));
        assert!(a <= lo && hi <= b, "{v:?} printed {}", outward(v));
        let text = inward(v);
        let (a, b) = parse(&text);
        assert!(lo <= a && b <= hi && a <= b, "{v:?} printed {text}");
    }
    assert_eq!(outward(Interval::new(1.0, 2.0)), "[1.00000, 2.00000]");
    assert_eq!(rounded(0.123456, true), "0.12345");
    assert_eq!(rounded(0.123451, false), "0.12346");
    assert_eq!(escape("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
}

/// Per bar as drawn: the solid rectangle's width and the light one's right end (`None` for an
/// open bar).
type Drawn = Vec<(f64, Option<f64>)>;

/// The bars' geometry as drawn ([`Drawn`]), and the axis's `(left, right, end value)`.
fn bars_drawn(svg: &str) -> (Drawn, (f64, f64, f64)) {
    let doc = roxmltree::Document::parse(svg).unwrap_or_else(|e| panic!("{e}\n{svg}"));
    let num = |n: roxmltree::Node, a: &str| -> f64 { n.attribute(a).unwrap().parse().unwrap() };
    let rects: Vec<roxmltree::Node> = doc
        .descendants()
        .filter(|n| n.has_tag_name("rect"))
        .collect();
    let paths = doc.descendants().filter(|n| n.has_tag_name("path")).count();
    let axis = doc.descendants().find(|n| n.has_tag_name("line")).unwrap();
    let end: f64 = doc
        .descendants()
        .filter(|n| n.has_tag_name("text"))
        .filter_map(|n| n.text()?.parse::<f64>().ok())
        .fold(0.0, f64::max);
    // Each bar: its light rectangle or open path, then its solid rectangle.
    let mut bars = Vec::new();
    let mut light = None;
    for r in &rects {
        if r.attribute("stroke").is_some() {
            light = Some(num(*r, "x") + num(*r, "width"));
        } else {
            bars.push((num(*r, "width"), light.take()));
        }
    }
    assert_eq!(
        rects.len() - bars.len() + paths,
        bars.len(),
        "one bracket per bar"
    );
    (bars, (num(axis, "x1"), num(axis, "x2"), end))
}

#[test]
fn brackets_are_drawn_to_scale_and_an_unproved_upper_bound_is_open() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand::rngs::StdRng::seed_from_u64(5);
    for _ in 0..200 {
        let n = rng.random_range(1..5);
        let bars: Vec<BracketBar> = (0..n)
            .map(|k| {
                let lower = rng.random_range(0.0..50.0) * 10f64.powi(rng.random_range(-3..3));
                let upper = if rng.random_range(0..5) == 0 {
                    f64::INFINITY
                } else {
                    lower * rng.random_range(1.0..3.0)
                };
                BracketBar {
                    label: format!("robot <{k}> & co"),
                    lower,
                    upper,
                }
            })
            .collect();
        let f = brackets_figure(&bars, "mm", "caption");
        let (drawn, (left, right, end)) = bars_drawn(&f.svg);
        assert_eq!(drawn.len(), n);
        let top = bars
            .iter()
            .map(|b| {
                if b.upper.is_finite() {
                    b.upper
                } else {
                    b.lower
                }
            })
            .fold(0.0, f64::max);
        assert!(
            end >= top && end <= 10.0 * top + 1.0,
            "axis to {end} for {top}"
        );
        let at = |v: f64| left + (right - left) * v / end;
        for (b, (solid, light)) in bars.iter().zip(&drawn) {
            assert!((left + solid - at(b.lower)).abs() < 0.02, "{b:?}");
            match light {
                Some(x) => {
                    assert!(b.upper.is_finite());
                    assert!(
                        (x - at(b.upper)).abs() < 0.02 || x - at(b.lower) <= 0.81,
                        "{b:?}"
                    );
                }
                None => assert!(!b.upper.is_finite(), "{b:?}"),
            }
        }
    }
}

#[test]
fn a_section_page_names_its_inputs_by_sha256_and_a_missing_one_is_an_error() {
    let dir = std::env::temp_dir().join(format!("calib-html-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("robot.toml");
    std::fs::write(&file, "x = 1\n").unwrap();
    let section = Section {
        heading: "Accuracy".into(),
        paragraphs: vec!["a < b & c".into()],
        ..Default::default()
    };
    let page = section_page("a robot", &section, &[("robot file", &file)]).unwrap();
    let options = roxmltree::ParsingOptions {
        allow_dtd: true,
        ..Default::default()
    };
    roxmltree::Document::parse_with_options(&page, options).expect("well-formed XML");
    assert!(page.contains(&format!("SHA-256 {}", sha256_hex(b"x = 1\n"))));
    assert!(page.contains("a &lt; b &amp; c"));
    let missing = dir.join("missing.toml");
    let e = section_page("a robot", &section, &[("robot file", &missing)]).unwrap_err();
    assert!(e.to_string().contains("missing.toml: cannot read"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}
