//! The HTML certificate end to end: `gough certify --report` and `gough reproduce --out` write one
//! well-formed, self-contained page that holds every leg's verdict, the input hashes and the
//! figures; it is written atomically, and never on bad input.

use crate::support;

use calib_gough::report_page::sha256_hex;
use std::path::Path;
use support::{certify, gough, simulate, tempdir};

/// Parses the page as XML (strictly: every element closed, attributes quoted, entities known) and
/// checks that it fetches nothing: no scripts, stylesheets, images, frames or objects, no `src`,
/// no link outside the page, no `url(` or `@import` in styles, and no address but the SVG
/// namespace. Returns the page's text (entities decoded), one text node per line.
fn check_page(html: &str) -> String {
    let doc = roxmltree::Document::parse_with_options(
        html,
        roxmltree::ParsingOptions {
            allow_dtd: true,
            ..Default::default()
        },
    )
    .unwrap_or_else(|e| panic!("the page is not well-formed: {e}"));
    let root = doc.root_element();
    assert_eq!(root.tag_name().name(), "html");
    for needed in ["head", "title", "body", "style"] {
        assert!(
            root.descendants().any(|n| n.has_tag_name(needed)),
            "<{needed}> missing"
        );
    }
    for n in root.descendants().filter(|n| n.is_element()) {
        let name = n.tag_name().name();
        assert!(
            !["script", "link", "img", "iframe", "object", "embed", "image", "audio", "video"]
                .contains(&name),
            "<{name}> would fetch or run something"
        );
        for a in n.attributes() {
            assert!(
                !["src", "srcset"].contains(&a.name()) && !a.name().starts_with("on"),
                "attribute {}",
                a.name()
            );
            if a.name() == "href" {
                assert!(
                    a.value().starts_with('#'),
                    "link out of the page: {}",
                    a.value()
                );
            }
            assert!(!a.value().contains("url("), "{}", a.value());
        }
    }
    let style: String = root
        .descendants()
        .filter(|n| n.has_tag_name("style"))
        .filter_map(|n| n.text())
        .collect();
    assert!(!style.contains("url(") && !style.contains("@import"));
    let without_ns = html.replace("http://www.w3.org/2000/svg", "");
    assert!(
        !without_ns.contains("http:") && !without_ns.contains("https:"),
        "an address in the page"
    );
    root.descendants()
        .filter(|n| n.is_text())
        .filter_map(|n| n.text())
        .map(str::trim)
        .filter(|t| !t.is_empty())
        .collect::<Vec<_>>()
        .join("\n")
}

/// The number of inline SVG figures in the page.
fn figures(html: &str) -> usize {
    html.matches("<svg ").count()
}

fn paths(dir: &Path) -> [String; 3] {
    ["robot.toml", "measurements.csv", "uncertainty.toml"]
        .map(|n| dir.join(n).display().to_string())
}

/// Every input's SHA-256, computed here from the file's bytes, is on the page.
fn assert_hashes(text: &str, dir: &Path) {
    for p in paths(dir) {
        let digest = sha256_hex(&std::fs::read(&p).unwrap());
        assert!(text.contains(&digest), "SHA-256 of {p} missing");
        assert!(text.contains(&p), "{p} missing");
    }
}

#[test]
fn certify_writes_a_self_contained_certificate_for_consistent_and_empty_legs() {
    let dir = tempdir("certificate");
    simulate(&dir, 3, &["--outlier", "5:2:0.3"]);
    let page = dir.join("certificate.html");
    let out = certify(&dir, &["--legs", "1,2", "--report", page.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2), "leg 2 holds an outlier");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let html = std::fs::read_to_string(&page).unwrap();
    let text = check_page(&html);
    // The summary counts, the culprit, each leg's verdict as the terminal says it.
    assert!(
        text.contains("1 of 2 legs certified consistent, 1 proved empty, 0"),
        "{text}"
    );
    assert!(text.contains("Leg 2 proved empty: culprit configuration 5 (measurements.csv line 6)"));
    for line in stdout.lines().filter(|l| l.starts_with("verdict:")) {
        assert!(text.contains(line), "`{line}` missing from the page");
    }
    assert_eq!(
        stdout.lines().filter(|l| l.starts_with("verdict:")).count(),
        2
    );
    assert!(text.contains("conflict: configuration 5 (measurements.csv line 6)"));
    for badge in ["consistent", "proved empty"] {
        assert!(text.lines().any(|l| l == badge), "badge {badge}");
    }
    assert_hashes(&text, &dir);
    assert!(text.contains("21 measured configurations"));
    assert!(text.contains(&format!("certicalib {}", env!("CARGO_PKG_VERSION"))));
    // Leg 1: projections and ranges; leg 2 (empty at once): projections only.
    assert_eq!(figures(&html), 3, "figures per leg");
    // Each leg's least-squares solution is placed against its certificate; on the empty leg it
    // is refuted only if it lies in x0 (beyond x0 nothing is proved).
    let lsq: Vec<&str> = text
        .lines()
        .filter(|l| l.starts_with("The least-squares solution"))
        .collect();
    assert_eq!(lsq.len(), 2, "{lsq:?}");
    assert!(
        text.lines()
            .any(|l| l.starts_with("Identifiability: weakly determined")),
        "what the configurations barely determine is on the page"
    );
    assert!(
        lsq[1].contains("lies in x0, where no parameter vector fits the measurements")
            || lsq[1].contains("lies outside x0 (in "),
        "{}",
        lsq[1]
    );
    // Nothing left behind but the page and the inputs.
    let stray: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with('.'))
        .collect();
    assert!(stray.is_empty(), "temporary files left: {stray:?}");
}

#[test]
fn the_certificate_names_tolerated_outliers() {
    let dir = tempdir("certificate-outliers");
    simulate(&dir, 3, &["--outlier", "5:2:0.3"]);
    let page = dir.join("c.html");
    let out = certify(
        &dir,
        &[
            "--legs",
            "2",
            "--max-outliers",
            "1",
            "--report",
            page.to_str().unwrap(),
        ],
    );
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = check_page(&std::fs::read_to_string(&page).unwrap());
    assert!(text.contains(
        "Leg 2: configuration 5 (measurements.csv line 6) proved to be outlier and tolerated."
    ));
    assert!(text.contains("outliers (at most 1 tolerated): configuration 5"));
    assert!(text.contains("1 of 1 legs certified consistent"));
}

#[test]
fn no_certificate_is_written_on_bad_input_or_an_unwritable_path() {
    let dir = tempdir("certificate-bad");
    simulate(&dir, 4, &[]);
    let page = dir.join("c.html");
    std::fs::write(dir.join("uncertainty.toml"), "pos = -1\n").unwrap();
    let out = certify(&dir, &["--legs", "1", "--report", page.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("uncertainty.toml"));
    assert!(!page.exists());
    simulate(&dir, 4, &[]);
    let nowhere = dir.join("missing-folder").join("c.html");
    let out = certify(
        &dir,
        &["--legs", "1", "--report", nowhere.to_str().unwrap()],
    );
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("missing-folder") && stderr.contains("certificate"),
        "{stderr}"
    );
}

#[test]
fn reproduce_writes_the_papers_figures_and_its_certificate() {
    let out_dir = tempdir("reproduce-report");
    let out = gough(&[
        "reproduce",
        "--samples",
        "30",
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let html = std::fs::read_to_string(out_dir.join("report.html")).unwrap();
    let text = check_page(&html);
    for needle in [
        "Table II",
        "Table III",
        "Table IV",
        "Fig. 3",
        "Fig. 4",
        "Fig. 5",
        "exact data",
    ] {
        assert!(text.contains(needle), "{needle} missing");
    }
    // Leg 1's two figures and the paper's three.
    assert_eq!(figures(&html), 5);
    // The embedded data are identified by the hashes of the files `gough simulate` writes.
    let data = tempdir("reproduce-data");
    simulate(&data, 2004, &[]);
    for name in ["robot.toml", "measurements.csv", "uncertainty.toml"] {
        let digest = sha256_hex(&std::fs::read(data.join(name)).unwrap());
        assert!(text.contains(&digest), "SHA-256 of {name} missing");
    }
    for f in ["fig3.svg", "fig4.svg", "fig5.svg"] {
        let svg = std::fs::read_to_string(out_dir.join(f)).unwrap();
        roxmltree::Document::parse(&svg).unwrap_or_else(|e| panic!("{f}: {e}"));
        assert!(
            html.contains(svg.trim()),
            "{f} is not the figure on the page"
        );
    }
}
