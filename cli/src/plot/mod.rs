//! Charts for reports, drawn with `plotters` into SVG or PNG (chosen by the file name): lines,
//! dashed lines and dots on linear or logarithmic axes, with vertical event markers.
//!
//! What makes them fit for a report: tick values are round (steps of 1, 2 or 5 × 10ᵏ; decades on
//! log axes, with 2 and 5 between them when the axis spans few decades), the legend has its own
//! column right of the data, sized to its longest entry, so it neither covers points nor is cut,
//! and a title too long for one line is wrapped. Lines are clipped to the data area (a curve
//! leaving the plot is cut at its edge, not squashed along it). Text is DejaVu Sans, embedded, so
//! a PNG looks the same on every machine; PNGs are drawn at twice the SVG's scale.

use std::path::{Path, PathBuf};
use std::sync::Once;

use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::FontStyle;

mod axis;
mod markers;
pub mod palette;
use axis::Axis;
pub use palette::{member_color, member_name};

/// A colour (red, green, blue).
pub type Rgb = (u8, u8, u8);

/// A palette that prints well in colour and in grey (matplotlib's first eight).
pub const COLORS: [Rgb; 8] = [
    (0x1f, 0x77, 0xb4),
    (0xd6, 0x27, 0x28),
    (0x2c, 0xa0, 0x2c),
    (0x94, 0x67, 0xbd),
    (0xff, 0x7f, 0x0e),
    (0x17, 0xbe, 0xcf),
    (0x8c, 0x56, 0x4b),
    (0x7f, 0x7f, 0x7f),
];

/// Linear or logarithmic (base 10) axis.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Scale {
    #[default]
    Linear,
    Log,
}

/// How a series is drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Style {
    /// A solid line.
    Line,
    /// A dashed line.
    Dashed,
    /// Dots.
    Points,
}

/// A named series of (x, y) points.
#[derive(Clone, Debug)]
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    pub style: Style,
    pub color: Rgb,
}

/// A vertical dotted line at `x` (an event); the legend has one entry per `kind`.
#[derive(Clone, Debug)]
pub struct Marker {
    pub x: f64,
    pub kind: String,
    pub color: Rgb,
}

/// A chart. Ranges not given are fitted to the data (rounded out to a tick step, or to decades
/// on a log axis).
#[derive(Clone, Debug, Default)]
pub struct Chart {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub x_scale: Scale,
    pub y_scale: Scale,
    pub x_range: Option<(f64, f64)>,
    pub y_range: Option<(f64, f64)>,
    pub series: Vec<Series>,
    pub markers: Vec<Marker>,
}

/// clap's check of a chart file name: it must end in `.svg` or `.png`.
pub fn plot_path(s: &str) -> Result<PathBuf, String> {
    match Format::of(Path::new(s)) {
        Some(_) => Ok(PathBuf::from(s)),
        None => Err(format!("{s}: the chart file must end in .svg or .png")),
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Format {
    Svg,
    Png,
}

impl Format {
    fn of(path: &Path) -> Option<Format> {
        match path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .as_deref()
        {
            Some("svg") => Some(Format::Svg),
            Some("png") => Some(Format::Png),
            _ => None,
        }
    }
}

/// The font family name under which DejaVu Sans is registered.
const FONT: &str = "sans-serif";

fn register_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // DejaVu Sans is a valid TrueType font; registration cannot fail on it.
        let _ = plotters::style::register_font(FONT, FontStyle::Normal, dejavu::sans::regular());
    });
}

/// Sizes in SVG pixels (a PNG multiplies them by its scale).
const PLOT_WIDTH: f64 = 760.0;
const HEIGHT: f64 = 500.0;
const TITLE_FONT: f64 = 18.0;
const LABEL_FONT: f64 = 15.0;
const TICK_FONT: f64 = 13.0;
const LEGEND_FONT: f64 = 13.0;
const PAD: f64 = 12.0;
const SWATCH: f64 = 30.0;

/// Width in pixels of `text` at `size` (DejaVu Sans metrics).
fn text_width(text: &str, size: f64) -> f64 {
    register_font();
    (FONT, size)
        .into_font()
        .box_size(text)
        .map_or(0.6 * size * text.chars().count() as f64, |(w, _)| {
            f64::from(w)
        })
}

/// Breaks `text` into lines no wider than `width` at `size`, at spaces.
fn wrap(text: &str, size: f64, width: f64) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for word in text.split(' ') {
        match lines.last_mut() {
            Some(line) if text_width(&format!("{line} {word}"), size) <= width => {
                line.push(' ');
                line.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    lines
}

/// Cuts the polyline `pts` (drawing coordinates) to the box `[x0, x1] × [y0, y1]`: the pieces
/// inside, each a polyline (Liang–Barsky on each segment).
fn clip(pts: &[(f64, f64)], (x0, x1): (f64, f64), (y0, y1): (f64, f64)) -> Vec<Vec<(f64, f64)>> {
    let mut pieces: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut open = false;
    for w in pts.windows(2) {
        let ((ax, ay), (bx, by)) = (w[0], w[1]);
        let (dx, dy) = (bx - ax, by - ay);
        let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
        let mut visible = true;
        for (p, q) in [(-dx, ax - x0), (dx, x1 - ax), (-dy, ay - y0), (dy, y1 - ay)] {
            if p == 0.0 {
                if q < 0.0 {
                    visible = false;
                }
            } else {
                let r = q / p;
                if p < 0.0 {
                    t0 = t0.max(r);
                } else {
                    t1 = t1.min(r);
                }
            }
        }
        if !visible || t0 > t1 {
            open = false;
            continue;
        }
        let a = (ax + t0 * dx, ay + t0 * dy);
        let b = (ax + t1 * dx, ay + t1 * dy);
        if !open || t0 > 0.0 {
            pieces.push(vec![a]);
        }
        pieces.last_mut().unwrap().push(b);
        open = t1 >= 1.0;
    }
    pieces
}

/// One legend entry.
struct Entry {
    name: String,
    style: Style,
    color: Rgb,
    /// A dotted marker line rather than a series.
    marker: bool,
}

fn rgb(c: Rgb) -> RGBColor {
    RGBColor(c.0, c.1, c.2)
}

fn px(v: f64, scale: f64) -> i32 {
    (v * scale).round() as i32
}

type Area<DB> = DrawingArea<DB, Shift>;

impl Chart {
    fn entries(&self) -> Vec<Entry> {
        let mut out: Vec<Entry> = self
            .series
            .iter()
            // A series without a name shares the entry of another (many records, one entry).
            .filter(|s| !s.name.is_empty())
            .map(|s| Entry {
                name: s.name.clone(),
                style: s.style,
                color: s.color,
                marker: false,
            })
            .collect();
        let ticks = markers::as_ticks(&self.markers);
        for k in markers::kinds(&self.markers) {
            out.push(Entry {
                name: markers::legend_name(&k, ticks),
                style: Style::Dashed,
                color: k.color,
                marker: true,
            });
        }
        out
    }

    fn axes(&self) -> (Axis, Axis) {
        let x = Axis::new(
            self.x_scale,
            self.x_range,
            self.series
                .iter()
                .flat_map(|s| s.points.iter().map(|p| p.0))
                .chain(self.markers.iter().map(|m| m.x)),
        );
        let y = Axis::new(
            self.y_scale,
            self.y_range,
            self.series
                .iter()
                .flat_map(|s| s.points.iter().map(|p| p.1)),
        );
        (x, y)
    }

    /// Width of the legend column (SVG pixels).
    fn legend_width(entries: &[Entry]) -> f64 {
        let text = entries
            .iter()
            .map(|e| text_width(&e.name, LEGEND_FONT))
            .fold(0.0, f64::max);
        if entries.is_empty() {
            PAD
        } else {
            text + SWATCH + 3.0 * PAD
        }
    }

    /// Writes the chart as SVG or PNG, chosen by the file name.
    pub fn write(&self, path: &Path) -> Result<(), String> {
        let bytes = match Format::of(path) {
            Some(Format::Svg) => self.to_svg()?.into_bytes(),
            Some(Format::Png) => self.to_png()?,
            None => {
                return Err(format!(
                    "{}: the chart file must end in .svg or .png",
                    path.display()
                ))
            }
        };
        crate::output::write_atomic(path, &bytes)
    }

    /// Writes `PREFIX-NAME.svg`, and `PREFIX-NAME.png` as well if `png`.
    pub fn write_named(&self, prefix: &Path, name: &str, png: bool) -> Result<(), String> {
        self.write(&crate::output::with_suffix(prefix, &format!("-{name}.svg")))?;
        if png {
            self.write(&crate::output::with_suffix(prefix, &format!("-{name}.png")))?;
        }
        Ok(())
    }

    /// Image size in SVG pixels, and the title's lines.
    fn layout(&self, entries: &[Entry]) -> ((f64, f64), Vec<String>) {
        let width = (PLOT_WIDTH + Self::legend_width(entries)).ceil();
        let title = wrap(&self.title, TITLE_FONT, width - 2.0 * PAD);
        // Below the title: HEIGHT less one title line, or taller when the legend needs it
        // (entries below the image's edge were cut: a column of thirty blocks showed 22).
        let legend = PAD + 10.0 + entries.len() as f64 * 1.6 * LEGEND_FONT + PAD;
        let rest = (HEIGHT - PAD - 1.3 * TITLE_FONT).max(legend);
        let height = PAD + title.len().max(1) as f64 * 1.3 * TITLE_FONT + rest;
        ((width, height.ceil()), title)
    }

    /// The chart as an SVG document.
    pub fn to_svg(&self) -> Result<String, String> {
        register_font();
        let entries = self.entries();
        let ((w, h), title) = self.layout(&entries);
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, (w as u32, h as u32)).into_drawing_area();
            self.draw(&root, &entries, &title, 1.0)?;
            root.present()
                .map_err(|e| format!("cannot draw the chart: {e}"))?;
        }
        Ok(svg)
    }

    /// The chart as PNG bytes, drawn at twice the SVG's scale.
    pub fn to_png(&self) -> Result<Vec<u8>, String> {
        register_font();
        const SCALE: f64 = 2.0;
        let entries = self.entries();
        let ((w, h), title) = self.layout(&entries);
        let (w, h) = ((w * SCALE) as u32, (h * SCALE) as u32);
        let mut buf = vec![0u8; (w * h * 3) as usize];
        {
            let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
            self.draw(&root, &entries, &title, SCALE)?;
            root.present()
                .map_err(|e| format!("cannot draw the chart: {e}"))?;
        }
        let mut png = Vec::new();
        let mut enc = png::Encoder::new(&mut png, w, h);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        enc.write_header()
            .and_then(|mut wr| wr.write_image_data(&buf))
            .map_err(|e| format!("cannot encode the PNG: {e}"))?;
        Ok(png)
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &Area<DB>,
        entries: &[Entry],
        title: &[String],
        s: f64,
    ) -> Result<(), String> {
        let err = |e: DrawingAreaErrorKind<DB::ErrorType>| format!("cannot draw the chart: {e}");
        root.fill(&WHITE).map_err(err)?;
        let (w, _) = root.dim_in_pixel();

        // Title, centred, one or more lines.
        let title_h = PAD + title.len() as f64 * 1.3 * TITLE_FONT;
        let (top, rest) = root.split_vertically(px(title_h, s));
        let style = TextStyle::from((FONT, TITLE_FONT * s).into_font())
            .pos(Pos::new(HPos::Center, VPos::Top));
        for (i, line) in title.iter().enumerate() {
            let y = PAD + i as f64 * 1.3 * TITLE_FONT;
            top.draw_text(line, &style, (w as i32 / 2, px(y, s)))
                .map_err(err)?;
        }

        // Data (left) and legend (right).
        let (plot, legend) = rest.split_horizontally(px(PLOT_WIDTH, s));
        let (xa, ya) = self.axes();
        let y_tick_w = ya
            .ticks
            .iter()
            .filter_map(|t| t.1.as_deref())
            .map(|l| text_width(l, TICK_FONT))
            .fold(0.0, f64::max);
        let ticks = markers::as_ticks(&self.markers);
        let kinds = markers::kinds(&self.markers);
        let strip = if ticks {
            kinds.len() as f64 * markers::TICK_ROW
        } else {
            0.0
        };
        let mut chart = ChartBuilder::on(&plot)
            .margin_top(px(PAD + strip, s))
            .margin_left(px(PAD, s))
            .margin_right(px(PAD, s))
            .margin_bottom(px(PAD / 2.0, s))
            .x_label_area_size(px(TICK_FONT + LABEL_FONT + 2.5 * PAD, s))
            .y_label_area_size(px(y_tick_w + LABEL_FONT + 2.5 * PAD, s))
            .build_cartesian_2d(xa.coord(), ya.coord())
            .map_err(err)?;
        let tick_font = (FONT, TICK_FONT * s).into_font();
        let label_font = (FONT, LABEL_FONT * s).into_font();
        let x_fmt = |u: &f64| xa.label(*u);
        let y_fmt = |u: &f64| ya.label(*u);
        chart
            .configure_mesh()
            .x_desc(self.x_label.as_str())
            .y_desc(self.y_label.as_str())
            .x_label_formatter(&x_fmt)
            .y_label_formatter(&y_fmt)
            .label_style(tick_font)
            .axis_desc_style(label_font)
            .bold_line_style(RGBColor(0xd8, 0xd8, 0xd8).stroke_width(px(1.0, s).max(1) as u32))
            .light_line_style(RGBColor(0xf0, 0xf0, 0xf0).stroke_width(px(1.0, s).max(1) as u32))
            .axis_style(RGBColor(0x40, 0x40, 0x40).stroke_width(px(1.0, s).max(1) as u32))
            .set_all_tick_mark_size(px(4.0, s))
            .draw()
            .map_err(err)?;

        let xr = (xa.to(xa.lo), xa.to(xa.hi));
        let yr = (ya.to(ya.lo), ya.to(ya.hi));
        let line_w = px(1.6, s).max(1) as u32;
        // Drawing units per pixel: lines keep a point only when it is half a pixel away from the
        // last kept one (a history of 10⁵ steps is drawn as a clean line, not 10⁵ thick stubs).
        let (px_x, px_y) = chart.plotting_area().get_pixel_range();
        let ux = (xr.1 - xr.0) / f64::from((px_x.end - px_x.start).max(1));
        let uy = (yr.1 - yr.0) / f64::from((px_y.end - px_y.start).max(1));
        let thin = |piece: Vec<(f64, f64)>| -> Vec<(f64, f64)> {
            let mut out: Vec<(f64, f64)> = Vec::with_capacity(piece.len());
            for (i, &p) in piece.iter().enumerate() {
                let keep = match out.last() {
                    None => true,
                    Some(l) => {
                        i + 1 == piece.len()
                            || (p.0 - l.0).abs() >= 2.0 * ux
                            || (p.1 - l.1).abs() >= 2.0 * uy
                    }
                };
                if keep {
                    out.push(p);
                }
            }
            out
        };
        if ticks {
            let area = chart.plotting_area();
            let top = area.map_coordinate(&(xr.0, yr.1)).1;
            let x_px = |x: f64| {
                let x = xa.drawable(x).then(|| xa.to(x))?;
                (xr.0..=xr.1)
                    .contains(&x)
                    .then(|| area.map_coordinate(&(x, yr.1)).0)
            };
            markers::draw_ticks(root, &self.markers, &kinds, top, x_px, s)?;
        }
        for m in self.markers.iter().filter(|m| !ticks && xa.drawable(m.x)) {
            let x = xa.to(m.x);
            if x < xr.0 || x > xr.1 {
                continue;
            }
            chart
                .plotting_area()
                .draw(&DashedPathElement::new(
                    vec![(x, yr.0), (x, yr.1)],
                    px(2.0, s),
                    px(3.0, s),
                    rgb(m.color).stroke_width(px(0.8, s).max(1) as u32),
                ))
                .map_err(err)?;
        }
        for series in &self.series {
            let pts: Vec<(f64, f64)> = series
                .points
                .iter()
                .filter(|(x, y)| xa.drawable(*x) && ya.drawable(*y))
                .map(|&(x, y)| (xa.to(x), ya.to(y)))
                .collect();
            let color = rgb(series.color);
            match series.style {
                Style::Points => {
                    let inside =
                        |&(x, y): &(f64, f64)| x >= xr.0 && x <= xr.1 && y >= yr.0 && y <= yr.1;
                    chart
                        .draw_series(
                            pts.into_iter()
                                .filter(inside)
                                .map(|p| Circle::new(p, px(2.6, s), color.filled())),
                        )
                        .map_err(err)?;
                }
                Style::Line => {
                    for piece in clip(&pts, xr, yr) {
                        chart
                            .plotting_area()
                            .draw(&PathElement::new(thin(piece), color.stroke_width(line_w)))
                            .map_err(err)?;
                    }
                }
                Style::Dashed => {
                    for piece in clip(&pts, xr, yr) {
                        chart
                            .plotting_area()
                            .draw(&DashedPathElement::new(
                                thin(piece),
                                px(7.0, s),
                                px(4.0, s),
                                color.stroke_width(line_w),
                            ))
                            .map_err(err)?;
                    }
                }
            }
        }

        // Legend: a column of entries level with the top of the data.
        let text_style = TextStyle::from((FONT, LEGEND_FONT * s).into_font())
            .pos(Pos::new(HPos::Left, VPos::Center));
        let x0 = px(PAD, s);
        for (i, e) in entries.iter().enumerate() {
            let y = px(PAD + 10.0 + i as f64 * 1.6 * LEGEND_FONT, s);
            let color = rgb(e.color);
            let (a, b) = ((x0, y), (x0 + px(SWATCH, s), y));
            match (e.style, e.marker) {
                (Style::Points, _) => legend
                    .draw(&Circle::new(
                        (x0 + px(SWATCH / 2.0, s), y),
                        px(3.2, s),
                        color.filled(),
                    ))
                    .map_err(err)?,
                (Style::Line, _) => legend
                    .draw(&PathElement::new(vec![a, b], color.stroke_width(line_w)))
                    .map_err(err)?,
                (Style::Dashed, marker) => {
                    let (dash, gap) = if marker { (2.0, 3.0) } else { (7.0, 4.0) };
                    legend
                        .draw(&DashedPathElement::new(
                            vec![a, b],
                            px(dash, s),
                            px(gap, s),
                            color.stroke_width(line_w),
                        ))
                        .map_err(err)?
                }
            }
            legend
                .draw_text(&e.name, &text_style, (x0 + px(SWATCH + PAD, s), y))
                .map_err(err)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests;
