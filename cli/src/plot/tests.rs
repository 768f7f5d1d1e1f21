//! Tests of the charts: clipping, titles, legends.

use super::*;

#[test]
fn lines_are_cut_at_the_edge() {
    let pieces = clip(
        &[(-1.0, 0.5), (0.5, 0.5), (2.0, 0.5)],
        (0.0, 1.0),
        (0.0, 1.0),
    );
    assert_eq!(pieces, vec![vec![(0.0, 0.5), (0.5, 0.5), (1.0, 0.5)]]);
    let pieces = clip(
        &[(0.5, 0.5), (0.5, 2.0), (0.6, 2.0), (0.6, 0.5)],
        (0.0, 1.0),
        (0.0, 1.0),
    );
    assert_eq!(
        pieces,
        vec![vec![(0.5, 0.5), (0.5, 1.0)], vec![(0.6, 1.0), (0.6, 0.5)]]
    );
}

#[test]
fn long_titles_wrap() {
    let t = "Thesis 4.2: two granite blocks, upper one released at 0.153 rad — no ground motion, and more words";
    let lines = wrap(t, TITLE_FONT, 400.0);
    assert!(lines.len() >= 2);
    assert!(lines.iter().all(|l| text_width(l, TITLE_FONT) <= 400.0));
    assert_eq!(lines.join(" "), t);
}

/// Both formats draw: the SVG has the title and every legend entry in full, the PNG is a
/// PNG of twice the SVG's size, and the image is widened for a long legend entry instead of
/// cutting it.
#[test]
fn svg_and_png_have_the_whole_legend() {
    let long = "Eq. 30, t1' = 0.323 s, beta = 1.48 (a long legend entry)";
    let chart = |name: &str| Chart {
        title: "OAS, test".into(),
        x_label: "p [1/s]".into(),
        y_label: "a_p / a_p,min".into(),
        series: vec![Series {
            name: name.into(),
            points: vec![(0.5, 1.0), (2.0, 3.0), (4.0, 9.7)],
            style: Style::Dashed,
            color: COLORS[2],
        }],
        ..Chart::default()
    };
    let svg = chart(long).to_svg().unwrap();
    assert!(svg.starts_with("<svg"));
    assert!(svg.contains("OAS, test"));
    assert!(svg.contains("beta = 1.48 (a long legend entry)"));
    let width = |svg: &str| -> u32 {
        let w = svg.split("width=\"").nth(1).unwrap();
        w[..w.find('"').unwrap()].parse().unwrap()
    };
    let short = chart("x").to_svg().unwrap();
    assert!(width(&svg) as f64 >= width(&short) as f64 + text_width(long, LEGEND_FONT) - 20.0);
    let png = chart(long).to_png().unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    let png_width = u32::from_be_bytes(png[16..20].try_into().unwrap());
    assert_eq!(png_width, 2 * width(&svg));
}

/// A legend longer than the default height makes the image taller, so that every entry is
/// drawn inside it (a column of thirty blocks showed 22 of its 30 entries); a short one keeps
/// the default height.
#[test]
fn a_long_legend_makes_the_image_taller() {
    let chart = |n: usize| Chart {
        title: "many series".into(),
        x_label: "t [s]".into(),
        y_label: "rotation [rad]".into(),
        series: (0..n)
            .map(|k| Series {
                name: format!("block {k}"),
                points: vec![(0.0, 0.0), (1.0, k as f64)],
                style: Style::Line,
                color: COLORS[k % COLORS.len()],
            })
            .collect(),
        ..Chart::default()
    };
    let attr = |svg: &str, name: &str| -> f64 {
        let v = svg.split(&format!("{name}=\"")).nth(1).unwrap();
        v[..v.find('"').unwrap()].parse().unwrap()
    };
    assert_eq!(attr(&chart(3).to_svg().unwrap(), "height"), HEIGHT);
    let svg = chart(40).to_svg().unwrap();
    let height = attr(&svg, "height");
    let last = svg.find(">\nblock 39\n<").expect("the last entry");
    let text = &svg[svg[..last].rfind("<text").unwrap()..last];
    let y = attr(text, " y");
    assert!(
        y + LEGEND_FONT < height,
        "entry at {y}, image {height} high"
    );
}
