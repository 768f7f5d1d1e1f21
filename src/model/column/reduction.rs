//! The FE route of thesis Appendix C: three mass points per block, the transformation `B` from
//! the interface DOFs to nodal displacements (Eq. C2, C11, C14), and the reduction
//! `M̃ = BᵀMB`, `p̃ = Bᵀp` (Eq. C6, C8). It gives the same `M` and `q` as the direct route of
//! [`Column::mass_matrix`] and [`Column::load_vector`] (tested).

use super::{Column, Pose};

/// The FE route of thesis Appendix C: `M̃ = BᵀMB` and `p̃ = Bᵀp` for a nodal mass matrix `M`
/// (`n_nodal × n_nodal`), a transformation `B` (`n_nodal × n_reduced`, nodal displacements from
/// reduced coordinates, Eq. C2) and nodal loads `p`. All matrices are column-major
/// (LAPACK / OpenSees `Matrix` storage). Outputs: `reduced_mass` (`n_reduced²`, column-major)
/// and `reduced_load` (`n_reduced`).
pub fn reduce(
    n_nodal: usize,
    n_reduced: usize,
    nodal_mass: &[f64],
    transformation: &[f64],
    nodal_load: &[f64],
    reduced_mass: &mut [f64],
    reduced_load: &mut [f64],
) {
    assert_eq!(nodal_mass.len(), n_nodal * n_nodal);
    assert_eq!(transformation.len(), n_nodal * n_reduced);
    assert_eq!(nodal_load.len(), n_nodal);
    assert_eq!(reduced_mass.len(), n_reduced * n_reduced);
    assert_eq!(reduced_load.len(), n_reduced);
    let bcol = |c: usize| &transformation[c * n_nodal..(c + 1) * n_nodal];
    // MB, column by column.
    let mut mb = vec![0.0; n_nodal];
    for c in 0..n_reduced {
        let b = bcol(c);
        for (r, v) in mb.iter_mut().enumerate() {
            *v = (0..n_nodal)
                .map(|k| nodal_mass[k * n_nodal + r] * b[k])
                .sum();
        }
        for r in 0..n_reduced {
            reduced_mass[c * n_reduced + r] = bcol(r).iter().zip(&mb).map(|(x, y)| x * y).sum();
        }
        reduced_load[c] = b.iter().zip(nodal_load).map(|(x, y)| x * y).sum();
    }
}

/// Three mass points per block (thesis Appendix C): on the block's axis at its bottom, centre
/// and top, with end masses `I / (2 (h/2)²)` and the rest in the middle, so that mass, centre and
/// moment of inertia are reproduced. Returns `(points, masses)` for the current geometry, block by
/// block (bottom, centre, top).
pub fn three_mass_points(column: &Column, pose: &Pose) -> Vec<([f64; 2], f64)> {
    let mut out = Vec::with_capacity(3 * column.n_interfaces());
    for (j, block) in column.blocks.iter().enumerate() {
        let half = 0.5 * block.height;
        let end = column.inertia[j] / (2.0 * half * half);
        let c = pose.centres[j];
        let a = pose.block_angles[j];
        // The block's axis in the current geometry.
        let axis = [-a.sin() * half, a.cos() * half];
        out.push(([c[0] - axis[0], c[1] - axis[1]], end));
        out.push((c, block.mass - 2.0 * end));
        out.push(([c[0] + axis[0], c[1] + axis[1]], end));
    }
    out
}

/// Transformation `B` of Appendix C (Eq. C2, C11, C14) from the `2n` interface DOFs to the
/// x and y displacements of the given points: `points[i]` belongs to block `owner[i]`. Rows are
/// all x components then all y components (`2·points` rows), column-major storage.
pub fn transformation_matrix(
    column: &Column,
    pose: &Pose,
    points: &[[f64; 2]],
    owner: &[usize],
) -> Vec<f64> {
    assert_eq!(points.len(), owner.len());
    let n = column.n_interfaces();
    let rows = 2 * points.len();
    let mut b = vec![0.0; rows * 2 * n];
    for a in 0..2 * n {
        let k = a % n;
        let p = pose.pivot(a);
        for (i, (r, &j)) in points.iter().zip(owner).enumerate() {
            if j >= k {
                // ẑ × (r − P) = (−(r−P)_y, (r−P)_x)
                b[a * rows + i] = -(r[1] - p[1]);
                b[a * rows + points.len() + i] = r[0] - p[0];
            }
        }
    }
    b
}
