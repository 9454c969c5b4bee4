//! The tests of `calib_pipeline::table`.

use calib_pipeline::*;
use std::path::Path;

fn header(cols: &[&str]) -> Vec<String> {
    cols.iter().map(|c| c.to_string()).collect()
}

#[test]
fn reads_numbers_and_names_every_problem() {
    let h = header(&["q1", "px"]);
    let f = Path::new("m.csv");
    let t = parse_number_table(f, "q1, px\n1, 2\n3,4e2\n", &h).unwrap();
    assert_eq!(t.rows, vec![vec![1.0, 2.0], vec![3.0, 400.0]]);
    assert_eq!(t.lines, vec![2, 3]);
    let e = parse_number_table(f, "q1,py\n1,2\n", &h).unwrap_err();
    assert_eq!((e.line, e.field.as_deref()), (Some(1), None));
    assert!(e.message.contains("expected `q1,px`"), "{e}");
    let e = parse_number_table(f, "q1,px\n1,2\n1,x\n", &h).unwrap_err();
    assert_eq!((e.line, e.field.as_deref()), (Some(3), Some("px")));
    let e = parse_number_table(f, "q1,px\n1,2\n1,NaN\n", &h).unwrap_err();
    assert_eq!((e.line, e.field.as_deref()), (Some(3), Some("px")));
    let e = parse_number_table(f, "q1,px\n1e300,2\n", &h).unwrap_err();
    assert_eq!((e.line, e.field.as_deref()), (Some(2), Some("q1")));
    // Every spelling of a non-finite number Rust's parser accepts, and a decimal that overflows.
    for bad in ["nan", "inf", "-inf", "infinity", "1e999", "-1e999"] {
        let e = parse_number_table(f, &format!("q1,px\n1,2\n{bad},2\n"), &h).unwrap_err();
        assert_eq!((e.line, e.field.as_deref()), (Some(3), Some("q1")), "{bad}");
        assert!(e.message.contains("expected a finite number"), "{bad}: {e}");
        let e = parse_named_columns(f, &format!("px;q1\n2;{bad}\n"), &h).unwrap_err();
        assert_eq!((e.line, e.field.as_deref()), (Some(2), Some("q1")), "{bad}");
    }
    let e = parse_number_table(f, "q1,px\n1,2,3\n", &h).unwrap_err();
    assert_eq!(e.line, Some(2));
    assert!(e.message.contains("columns"), "{e}");
}

#[test]
fn named_columns_come_out_of_a_european_export_in_the_order_asked() {
    let f = Path::new("t.csv");
    let text = "Stamp;b;a;c\n2,02011E+13;1,5;-2;x\n0;3;4,25;y\n";
    let t = parse_named_columns(f, text, &header(&["a", "b"])).unwrap();
    assert_eq!(t.rows, vec![vec![-2.0, 1.5], vec![4.25, 3.0]]);
    assert_eq!(t.lines, vec![2, 3]);
    // A comma-separated file keeps its decimal points, tabs are found too.
    let t = parse_named_columns(f, "a,b\n1.5,2\n", &header(&["b"])).unwrap();
    assert_eq!(t.rows, vec![vec![2.0]]);
    // CRLF line ends: the same lines.
    let t = parse_named_columns(f, "a;b\r\n1,5;2\r\n3;4\r\n", &header(&["b"])).unwrap();
    assert_eq!((t.rows.len(), t.lines.clone()), (2, vec![2, 3]));
    let t = parse_named_columns(f, "a\tb\n1,5\t2\n", &header(&["a"])).unwrap();
    assert_eq!(t.rows, vec![vec![1.5]]);
    // A missing column is named, with the columns there are; a bad cell by line and field.
    let e = parse_named_columns(f, text, &header(&["z"])).unwrap_err();
    assert_eq!((e.line, e.field.as_deref()), (Some(1), Some("z")));
    assert!(e.message.contains("Stamp, b, a, c"), "{e}");
    assert!(e.message.contains("';'-separated, decimal commas"), "{e}");
    let e = parse_named_columns(f, text, &header(&["c"])).unwrap_err();
    assert_eq!((e.line, e.field.as_deref()), (Some(2), Some("c")));
}
