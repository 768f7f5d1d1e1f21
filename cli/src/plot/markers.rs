//! Event markers. A few are dotted lines across the data; many (the impacts of a column of
//! drums run to the end of a record: 25 000 on thirty drums) are short ticks in a strip above
//! the data, one row per kind — as lines they hid every curve under a wall of colour, and as
//! SVG they were two million dash elements (195 MB).

use plotters::prelude::*;

use super::{px, rgb, Area, Marker, Rgb};

/// Beyond this many markers a chart draws them as ticks above the data.
pub(super) const MAX_MARKER_LINES: usize = 100;

/// Height of one row of ticks (SVG pixels).
pub(super) const TICK_ROW: f64 = 8.0;

/// One kind of marker: its name, colour and how many there are.
pub(super) struct Kind {
    pub name: String,
    pub color: Rgb,
    pub count: usize,
}

/// The kinds of `markers` in order of first appearance (the legend's order).
pub(super) fn kinds(markers: &[Marker]) -> Vec<Kind> {
    let mut out: Vec<Kind> = Vec::new();
    for m in markers {
        match out.iter_mut().find(|k| k.name == m.kind) {
            Some(k) => k.count += 1,
            None => out.push(Kind {
                name: m.kind.clone(),
                color: m.color,
                count: 1,
            }),
        }
    }
    out
}

/// Whether `markers` are drawn as ticks above the data rather than lines across it.
pub(super) fn as_ticks(markers: &[Marker]) -> bool {
    markers.len() > MAX_MARKER_LINES
}

/// The legend's name of a kind: as given for lines; with the count for ticks, which cannot be
/// counted by eye.
pub(super) fn legend_name(kind: &Kind, ticks: bool) -> String {
    if ticks {
        format!("{} ({}, ticks above)", kind.name, kind.count)
    } else {
        kind.name.clone()
    }
}

/// Draws `markers` as ticks on `root` (the whole image, backend pixels) in rows above `top` (the
/// data's top edge, backend pixels), row `i` for `kinds[i]`; `x_px` maps a marker's data x to
/// its pixel column, `None` outside the data. One tick per pixel column and kind.
pub(super) fn draw_ticks<DB: DrawingBackend>(
    root: &Area<DB>,
    markers: &[Marker],
    kinds: &[Kind],
    top: i32,
    x_px: impl Fn(f64) -> Option<i32>,
    s: f64,
) -> Result<(), String> {
    let row = px(TICK_ROW, s);
    let width = px(1.0, s).max(1) as u32;
    for (i, kind) in kinds.iter().enumerate() {
        let mut columns: Vec<i32> = markers
            .iter()
            .filter(|m| m.kind == kind.name)
            .filter_map(|m| x_px(m.x))
            .collect();
        columns.sort_unstable();
        columns.dedup();
        let y1 = top - px(2.0, s) - i as i32 * row;
        let y0 = y1 - row + px(2.0, s);
        for x in columns {
            root.draw(&PathElement::new(
                vec![(x, y0), (x, y1)],
                rgb(kind.color).stroke_width(width),
            ))
            .map_err(|e| format!("cannot draw the chart: {e}"))?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::super::{Chart, Series, Style, COLORS};
    use super::*;

    fn chart(markers: usize) -> Chart {
        Chart {
            title: "markers".into(),
            x_label: "t [s]".into(),
            y_label: "rotation [rad]".into(),
            series: vec![Series {
                name: "drum 0".into(),
                points: (0..=100)
                    .map(|i| (i as f64 * 0.1, (i as f64).sin()))
                    .collect(),
                style: Style::Line,
                color: COLORS[0],
            }],
            markers: (0..markers)
                .map(|i| Marker {
                    x: 10.0 * i as f64 / markers as f64,
                    kind: if i % 3 == 0 { "lift_off" } else { "impact" }.into(),
                    color: if i % 3 == 0 { COLORS[4] } else { COLORS[1] },
                })
                .collect(),
            ..Chart::default()
        }
    }

    /// Many markers are ticks above the data: the SVG stays small (one element per pixel column
    /// and kind, not dozens of dashes per marker) and the legend gives the counts; a few stay
    /// lines, named as given.
    #[test]
    fn many_markers_are_ticks_above_the_data() {
        let many = chart(20_000).to_svg().unwrap();
        let impact = "#D62728"; // COLORS[1]
        assert!(
            many.matches(impact).count() < 2_000,
            "{} elements",
            many.matches(impact).count()
        );
        assert!(many.contains("impact (13333, ticks above)"), "legend");
        assert!(many.contains("lift_off (6667, ticks above)"), "legend");
        let few = chart(30).to_svg().unwrap();
        assert!(few.contains(">\nimpact\n<") && !few.contains("ticks above"));
        assert!(few.matches(impact).count() > 20);
        assert!(many.len() < 400_000, "{} bytes", many.len());
        assert_eq!(&chart(20_000).to_png().unwrap()[..4], b"\x89PNG");
    }

    #[test]
    fn kinds_keep_their_first_order_and_count() {
        let k = kinds(&chart(7).markers);
        let got: Vec<(&str, usize)> = k.iter().map(|k| (k.name.as_str(), k.count)).collect();
        assert_eq!(got, [("lift_off", 3), ("impact", 4)]);
    }
}
