//! The convex hull of a transformed OAS (thesis Fig. 48–49): the left edge of the convex hull of
//! the unsafe region of the `(f, a_p / a_p,min)` plane.
//!
//! At each level every size up to the largest unsafe one is taken as unsafe, so the unsafe region
//! is the set right of the boundary points `(f_k, L_k)` (larger `f`: smaller blocks). Its convex
//! hull is bounded on the left by the greatest convex function of the level below every boundary
//! point: the lower convex envelope of the points `(L_k, f_k)` with `L` as abscissa. Its
//! smallest `f` is `f_min` (Eq. 20); divided by `f_min` it starts at 1, the vertical line of the
//! simplified transformed OAS (Eq. 21), and its departure from 1 at higher levels is how
//! conservative that line is there.

use super::{Oas, OasPoint};

/// The left edge of the convex hull of a transformed OAS.
#[derive(Clone, Debug, PartialEq)]
pub struct TransformedHull {
    /// The hull's vertices `(level, f)`, by increasing level: a polyline, convex in the level.
    pub vertices: Vec<(f64, f64)>,
    /// `f_min`, the smallest `f` of the vertices \[1/s\].
    pub f_min: f64,
}

impl TransformedHull {
    /// The hull of the points `(level, f)` (any order); `None` without a point or with a point
    /// that is not finite.
    pub fn of_points(points: &[(f64, f64)]) -> Option<TransformedHull> {
        if points.is_empty() || points.iter().any(|p| !p.0.is_finite() || !p.1.is_finite()) {
            return None;
        }
        let mut pts = points.to_vec();
        // By level; at equal levels only the smallest f can be on the lower envelope.
        pts.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
        pts.dedup_by(|b, a| a.0 == b.0);
        // Andrew's monotone chain, lower half: drop the middle of every turn that is not
        // strictly convex (collinear vertices are dropped too).
        let mut hull: Vec<(f64, f64)> = Vec::with_capacity(pts.len());
        for p in pts {
            while hull.len() >= 2 {
                let (a, b) = (hull[hull.len() - 2], hull[hull.len() - 1]);
                let cross = (b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0);
                if cross <= 0.0 {
                    hull.pop();
                } else {
                    break;
                }
            }
            hull.push(p);
        }
        let f_min = hull.iter().map(|v| v.1).fold(f64::INFINITY, f64::min);
        Some(TransformedHull {
            vertices: hull,
            f_min,
        })
    }

    /// The hull of the boundary of `oas` (`None` when nothing overturns).
    pub fn of(oas: &Oas) -> Option<TransformedHull> {
        let pts: Vec<(f64, f64)> = oas
            .boundary()
            .iter()
            .map(|q: &OasPoint| (q.level, q.f))
            .collect();
        TransformedHull::of_points(&pts)
    }

    /// The hull's `f` at `level`, linear between vertices; `None` outside the vertices' levels.
    pub fn at(&self, level: f64) -> Option<f64> {
        let first = self.vertices.first()?;
        let last = self.vertices.last()?;
        if level < first.0 || level > last.0 {
            return None;
        }
        if self.vertices.len() == 1 {
            return Some(first.1);
        }
        let k = self
            .vertices
            .windows(2)
            .position(|w| level <= w[1].0)
            .unwrap_or(self.vertices.len() - 2);
        let (a, b) = (self.vertices[k], self.vertices[k + 1]);
        Some(a.1 + (b.1 - a.1) * (level - a.0) / (b.0 - a.0))
    }

    /// The vertices `(level, f / f_min)` (thesis Fig. 49: "normalized by their lowest horizontal
    /// coordinate").
    pub fn normalised(&self) -> Vec<(f64, f64)> {
        self.vertices
            .iter()
            .map(|&(l, f)| (l, f / self.f_min))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_hull_is_the_lower_convex_envelope() {
        // Levels 1..=6; f dips at level 2, bulges left (smaller f) at 4 between 3 and 5, and a
        // second point at level 5 with a larger f is not on the envelope.
        let pts = [
            (3.0, 5.0),
            (1.0, 6.0),
            (2.0, 4.0),
            (4.0, 5.5),
            (5.0, 7.0),
            (5.0, 9.0),
            (6.0, 12.0),
        ];
        let h = TransformedHull::of_points(&pts).unwrap();
        // (3, 5) lies above the chord from (2, 4) to (4, 5.5) (4.75 < 5): not a vertex.
        assert_eq!(
            h.vertices,
            vec![(1.0, 6.0), (2.0, 4.0), (4.0, 5.5), (5.0, 7.0), (6.0, 12.0)]
        );
        assert_eq!(h.f_min, 4.0);
        // Every point is on or right of the hull, and the hull is convex.
        for p in pts {
            assert!(h.at(p.0).unwrap() <= p.1 + 1e-12, "{p:?}");
        }
        let slopes: Vec<f64> = h
            .vertices
            .windows(2)
            .map(|w| (w[1].1 - w[0].1) / (w[1].0 - w[0].0))
            .collect();
        assert!(slopes.windows(2).all(|s| s[1] > s[0]), "{slopes:?}");
        assert_eq!(h.at(3.0), Some(4.75));
        assert_eq!(h.at(0.5), None);
        assert_eq!(h.at(6.5), None);
        let n = h.normalised();
        assert_eq!(n[1], (2.0, 1.0));
        assert_eq!(n[0], (1.0, 1.5));
    }

    #[test]
    fn collinear_points_and_edge_cases() {
        // A vertical line of the transformed OAS (f constant): only its two ends remain.
        let h = TransformedHull::of_points(&[(1.0, 2.0), (2.0, 2.0), (3.0, 2.0)]).unwrap();
        assert_eq!(h.vertices, vec![(1.0, 2.0), (3.0, 2.0)]);
        assert_eq!(h.at(2.5), Some(2.0));
        let one = TransformedHull::of_points(&[(2.0, 3.0)]).unwrap();
        assert_eq!(one.at(2.0), Some(3.0));
        assert_eq!(one.normalised(), vec![(2.0, 1.0)]);
        assert!(TransformedHull::of_points(&[]).is_none());
        assert!(TransformedHull::of_points(&[(1.0, f64::NAN)]).is_none());
    }
}
