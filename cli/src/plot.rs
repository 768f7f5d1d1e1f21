//! Charts for reports: lines, points and event markers on linear or logarithmic axes, written as
//! SVG (hand-made, no dependency) or PNG (the SVG rendered with resvg).

use std::fmt::Write as _;
use std::path::Path;

/// How a series is drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Style {
    /// A solid polyline.
    Line,
    /// A dashed polyline.
    Dashed,
    /// Dots (spectra: one dot per overturning point).
    #[allow(dead_code)]
    Points,
}

/// A named series of (x, y) points.
#[derive(Clone, Debug)]
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    pub style: Style,
    pub color: &'static str,
}

/// A vertical marker (an event) at `x`.
#[derive(Clone, Debug)]
pub struct Marker {
    pub x: f64,
    pub label: String,
    pub color: &'static str,
}

/// A chart.
#[derive(Clone, Debug, Default)]
pub struct Chart {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub x_log: bool,
    pub y_log: bool,
    pub series: Vec<Series>,
    pub markers: Vec<Marker>,
}

/// A palette that prints well in colour and in grey.
pub const COLORS: [&str; 8] = [
    "#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b", "#7f7f7f",
];

const WIDTH: f64 = 900.0;
const HEIGHT: f64 = 520.0;
const LEFT: f64 = 80.0;
const RIGHT: f64 = 190.0;
const TOP: f64 = 50.0;
const BOTTOM: f64 = 60.0;

fn nice_step(span: f64) -> f64 {
    let raw = span / 6.0;
    let mag = 10f64.powf(raw.log10().floor());
    let f = raw / mag;
    mag * if f < 1.5 {
        1.0
    } else if f < 3.5 {
        2.0
    } else if f < 7.5 {
        5.0
    } else {
        10.0
    }
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

fn fmt_tick(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else if v.abs() >= 1e4 || v.abs() < 1e-3 {
        format!("{v:.0e}")
    } else {
        let s = format!("{v:.4}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

impl Chart {
    fn range(&self, x: bool) -> (f64, f64) {
        let log = if x { self.x_log } else { self.y_log };
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        for s in &self.series {
            for &(px, py) in &s.points {
                let v = if x { px } else { py };
                if v.is_finite() && (!log || v > 0.0) {
                    lo = lo.min(v);
                    hi = hi.max(v);
                }
            }
        }
        if x {
            for m in &self.markers {
                lo = lo.min(m.x);
                hi = hi.max(m.x);
            }
        }
        if !lo.is_finite() {
            return if log { (1.0, 10.0) } else { (0.0, 1.0) };
        }
        if log {
            (
                10f64.powf(lo.log10().floor()),
                10f64.powf(hi.log10().ceil().max(lo.log10().floor() + 1.0)),
            )
        } else if hi - lo < 1e-300 {
            (lo - 1.0, hi + 1.0)
        } else {
            let step = nice_step(hi - lo);
            ((lo / step).floor() * step, (hi / step).ceil() * step)
        }
    }

    /// The chart as an SVG document.
    pub fn to_svg(&self) -> String {
        let (x0, x1) = self.range(true);
        let (y0, y1) = self.range(false);
        let pw = WIDTH - LEFT - RIGHT;
        let ph = HEIGHT - TOP - BOTTOM;
        let tx = |v: f64| {
            let f = if self.x_log {
                (v.log10() - x0.log10()) / (x1.log10() - x0.log10())
            } else {
                (v - x0) / (x1 - x0)
            };
            LEFT + f * pw
        };
        let ty = |v: f64| {
            let f = if self.y_log {
                (v.log10() - y0.log10()) / (y1.log10() - y0.log10())
            } else {
                (v - y0) / (y1 - y0)
            };
            TOP + (1.0 - f) * ph
        };
        let mut s = String::new();
        let _ = writeln!(
            s,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{HEIGHT}" viewBox="0 0 {WIDTH} {HEIGHT}" font-family="DejaVu Sans, Arial, sans-serif" font-size="13">"#
        );
        let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
        let _ = writeln!(
            s,
            r#"<text x="{}" y="28" font-size="16" text-anchor="middle">{}</text>"#,
            LEFT + pw / 2.0,
            escape(&self.title)
        );
        // Grid and ticks.
        let ticks = |lo: f64, hi: f64, log: bool| -> Vec<f64> {
            if log {
                let (a, b) = (lo.log10().round() as i32, hi.log10().round() as i32);
                (a..=b).map(|e| 10f64.powi(e)).collect()
            } else {
                let step = nice_step(hi - lo);
                let mut v = Vec::new();
                let mut t = (lo / step).ceil() * step;
                while t <= hi + 1e-9 * step {
                    v.push(if t.abs() < 1e-12 * step { 0.0 } else { t });
                    t += step;
                }
                v
            }
        };
        for t in ticks(x0, x1, self.x_log) {
            let x = tx(t);
            let _ = writeln!(
                s,
                r##"<line x1="{x:.1}" y1="{TOP}" x2="{x:.1}" y2="{:.1}" stroke="#e0e0e0"/>"##,
                TOP + ph
            );
            let _ = writeln!(
                s,
                r#"<text x="{x:.1}" y="{:.1}" text-anchor="middle">{}</text>"#,
                TOP + ph + 18.0,
                fmt_tick(t)
            );
        }
        for t in ticks(y0, y1, self.y_log) {
            let y = ty(t);
            let _ = writeln!(
                s,
                r##"<line x1="{LEFT}" y1="{y:.1}" x2="{:.1}" y2="{y:.1}" stroke="#e0e0e0"/>"##,
                LEFT + pw
            );
            let _ = writeln!(
                s,
                r#"<text x="{:.1}" y="{:.1}" text-anchor="end">{}</text>"#,
                LEFT - 6.0,
                y + 4.0,
                fmt_tick(t)
            );
        }
        let _ = writeln!(
            s,
            r##"<rect x="{LEFT}" y="{TOP}" width="{pw}" height="{ph}" fill="none" stroke="#333"/>"##
        );
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{:.1}" text-anchor="middle">{}</text>"#,
            LEFT + pw / 2.0,
            HEIGHT - 15.0,
            escape(&self.x_label)
        );
        let _ = writeln!(
            s,
            r#"<text x="20" y="{:.1}" text-anchor="middle" transform="rotate(-90 20 {:.1})">{}</text>"#,
            TOP + ph / 2.0,
            TOP + ph / 2.0,
            escape(&self.y_label)
        );
        // Markers.
        for m in &self.markers {
            let x = tx(m.x);
            let _ = writeln!(
                s,
                r#"<line x1="{x:.1}" y1="{TOP}" x2="{x:.1}" y2="{:.1}" stroke="{}" stroke-width="0.8" stroke-dasharray="2,3"><title>{}</title></line>"#,
                TOP + ph,
                m.color,
                escape(&m.label)
            );
        }
        // Series, clipped to the plot.
        let _ = writeln!(
            s,
            r#"<clipPath id="plot"><rect x="{LEFT}" y="{TOP}" width="{pw}" height="{ph}"/></clipPath><g clip-path="url(#plot)">"#
        );
        for series in &self.series {
            let pts: Vec<(f64, f64)> = series
                .points
                .iter()
                .filter(|(x, y)| {
                    x.is_finite()
                        && y.is_finite()
                        && (!self.x_log || *x > 0.0)
                        && (!self.y_log || *y > 0.0)
                })
                .map(|&(x, y)| (tx(x), ty(y)))
                .collect();
            match series.style {
                Style::Points => {
                    for (x, y) in pts {
                        let _ = writeln!(
                            s,
                            r#"<circle cx="{x:.1}" cy="{y:.1}" r="2.2" fill="{}"/>"#,
                            series.color
                        );
                    }
                }
                Style::Line | Style::Dashed => {
                    let mut d = String::new();
                    for (i, (x, y)) in pts.iter().enumerate() {
                        let _ = write!(d, "{}{x:.2},{y:.2} ", if i == 0 { "M" } else { "L" });
                    }
                    let dash = if series.style == Style::Dashed {
                        r#" stroke-dasharray="7,4""#
                    } else {
                        ""
                    };
                    let _ = writeln!(
                        s,
                        r#"<path d="{d}" fill="none" stroke="{}" stroke-width="1.4"{dash}/>"#,
                        series.color
                    );
                }
            }
        }
        let _ = writeln!(s, "</g>");
        // Legend.
        let mut ly = TOP + 10.0;
        let lx = LEFT + pw + 15.0;
        for series in &self.series {
            match series.style {
                Style::Points => {
                    let _ = writeln!(
                        s,
                        r#"<circle cx="{:.1}" cy="{:.1}" r="3" fill="{}"/>"#,
                        lx + 12.0,
                        ly,
                        series.color
                    );
                }
                _ => {
                    let dash = if series.style == Style::Dashed {
                        r#" stroke-dasharray="7,4""#
                    } else {
                        ""
                    };
                    let _ = writeln!(
                        s,
                        r#"<line x1="{lx}" y1="{ly:.1}" x2="{:.1}" y2="{ly:.1}" stroke="{}" stroke-width="2"{dash}/>"#,
                        lx + 24.0,
                        series.color
                    );
                }
            }
            let _ = writeln!(
                s,
                r#"<text x="{:.1}" y="{:.1}">{}</text>"#,
                lx + 30.0,
                ly + 4.0,
                escape(&series.name)
            );
            ly += 20.0;
        }
        let mut kinds: Vec<(&str, &str)> = Vec::new();
        for m in &self.markers {
            let kind = m.label.split_whitespace().next().unwrap_or("");
            if !kinds.iter().any(|(k, _)| *k == kind) {
                kinds.push((kind, m.color));
            }
        }
        for (kind, color) in kinds {
            let _ = writeln!(
                s,
                r#"<line x1="{lx}" y1="{ly:.1}" x2="{:.1}" y2="{ly:.1}" stroke="{color}" stroke-dasharray="2,3" stroke-width="1.5"/>"#,
                lx + 24.0
            );
            let _ = writeln!(
                s,
                r#"<text x="{:.1}" y="{:.1}">{}</text>"#,
                lx + 30.0,
                ly + 4.0,
                escape(kind)
            );
            ly += 20.0;
        }
        s.push_str("</svg>\n");
        s
    }

    /// Writes the chart as SVG or PNG, chosen by the file extension.
    pub fn write(&self, path: &Path) -> Result<(), String> {
        let svg = self.to_svg();
        match path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .as_deref()
        {
            Some("svg") => crate::output::write_atomic(path, svg.as_bytes()),
            Some("png") => {
                let png = svg_to_png(&svg)?;
                crate::output::write_atomic(path, &png)
            }
            _ => Err(format!(
                "{}: the plot file must end in .svg or .png",
                path.display()
            )),
        }
    }
}

/// Renders an SVG document to PNG bytes (system fonts for the text).
pub fn svg_to_png(svg: &str) -> Result<Vec<u8>, String> {
    use resvg::{tiny_skia, usvg};
    let mut opt = usvg::Options::default();
    let fonts = opt.fontdb_mut();
    fonts.load_system_fonts();
    // Generic families map to fonts that Debian has (fontdb's defaults are Windows names).
    fonts.set_sans_serif_family("DejaVu Sans");
    fonts.set_serif_family("DejaVu Serif");
    fonts.set_monospace_family("DejaVu Sans Mono");
    let tree =
        usvg::Tree::from_str(svg, &opt).map_err(|e| format!("cannot render the plot: {e}"))?;
    let size = tree.size().to_int_size();
    let mut pixmap =
        tiny_skia::Pixmap::new(size.width(), size.height()).ok_or("cannot allocate the image")?;
    resvg::render(&tree, tiny_skia::Transform::default(), &mut pixmap.as_mut());
    pixmap
        .encode_png()
        .map_err(|e| format!("cannot encode the PNG: {e}"))
}
