//! Column geometry and the interface mass matrix (SPEC §1, thesis Eq. 4–6 and Appendix C).
//!
//! A column is a stack of rigid blocks, bottom (index 0) to top. Interface `k` is the joint under
//! block `k`. Every interface has two rotational degrees of freedom, ordered
//! `phi = [phĭ_0 … phĭ_{n-1}, phî_0 … phî_{n-1}]`: `phĭ_k` is the rotation of everything above
//! interface `k` about its RIGHT corner (admissible `<= 0`), `phî_k` about its LEFT corner
//! (admissible `>= 0`). Angles are counter-clockwise positive, x to the right, y up.
//!
//! The geometry is recomputed from the angles (large rotations), and the mass matrix and load
//! vector are those of the current, rotated geometry:
//! `M[a][b] = Σ_{j ≥ max(k_a, k_b)} ( m_j (c_j − P_a)·(c_j − P_b) + I_j )` and
//! `q[a] = Σ_{j ≥ k_a} ( −(c_j − P_a)_y F_jx + (c_j − P_a)_x F_jy )` with
//! `F_j = (−m_j a_g, −m_j g)`. This is exactly `BᵀMB` and `Bᵀp` of thesis Appendix C.
//!
//! Here: the blocks and the validated column; [`Pose`] (`pose.rs`) the current geometry;
//! `mass_matrix.rs` `M`, `q` and the velocity terms; `reduction.rs` the FE route of Appendix C.

mod mass_matrix;
mod pose;
mod reduction;

pub(crate) use pose::BlockMap;
pub use pose::Pose;
pub use reduction::{reduce, three_mass_points, transformation_matrix};

use crate::validate::{positive, InvalidValue};

/// Standard acceleration of gravity used by the thesis (m/s²).
pub const GRAVITY: f64 = 9.81;

/// One rigid block of a column.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Block {
    /// Width `w` (m).
    pub width: f64,
    /// Height `h` (m).
    pub height: f64,
    /// Mass `m` (kg).
    pub mass: f64,
    /// Moment of inertia about the centre of mass (kg m²); `None` is the uniform rectangle
    /// `m (w² + h²) / 12`.
    pub inertia: Option<f64>,
    /// Width of the contact under this block (its interface with the block below or the ground);
    /// `None` is `min(w_{k-1}, w_k)` (`w_0` on the ground). Cut corners (thesis Fig. 59, Table 1)
    /// and the experiments of section 4 have narrower contacts than the blocks.
    pub contact_width: Option<f64>,
}

impl Block {
    /// A uniform rectangular block with full contact.
    pub fn rectangle(width: f64, height: f64, mass: f64) -> Block {
        Block {
            width,
            height,
            mass,
            inertia: None,
            contact_width: None,
        }
    }
}

/// Why a column could not be built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ColumnError {
    /// A column needs at least one block.
    #[error("a column needs at least one block")]
    Empty,
    /// More blocks than the models' supported maximum of interfaces
    /// ([`crate::model::configuration::MAX_INTERFACES`]), refused before anything is allocated
    /// for them.
    #[error(
        "{blocks} blocks: a column has at most {} (one interface per block)",
        crate::model::configuration::MAX_INTERFACES
    )]
    TooManyBlocks {
        /// The number of blocks given.
        blocks: usize,
    },
    /// A block's field (`width`, `height`, `mass`, `inertia`, `contact_width`) is not a finite
    /// number greater than zero, or the contact is wider than the blocks it joins.
    #[error("block {block}: {invalid}")]
    InvalidBlock {
        /// 0-based block index, bottom = 0.
        block: usize,
        /// The field, its value and the rule it breaks.
        invalid: InvalidValue,
    },
    /// Finite inputs whose derived geometry is not finite in double precision: a block's
    /// inertia `m (w² + h²) / 12` when none is given, or the column's height.
    #[error("block {block}: {quantity} is not finite in double precision: the inputs are too large (use other units)")]
    TooLarge {
        /// 0-based block index, bottom = 0.
        block: usize,
        /// What overflowed, with the inputs it came from.
        quantity: String,
    },
}

/// A validated column of rigid blocks with its reference (straight) geometry.
#[derive(Clone, Debug, PartialEq)]
pub struct Column {
    blocks: Vec<Block>,
    /// Half contact width `b_k` of each interface.
    half_contact: Vec<f64>,
    /// Height of interface `k` in the straight column, `Σ_{j<k} h_j`.
    base_height: Vec<f64>,
    /// Moment of inertia of each block about its centre.
    inertia: Vec<f64>,
}

impl Column {
    /// Validates the blocks and precomputes the reference geometry.
    pub fn new(blocks: Vec<Block>) -> Result<Column, ColumnError> {
        if blocks.is_empty() {
            return Err(ColumnError::Empty);
        }
        if blocks.len() > crate::model::configuration::MAX_INTERFACES {
            return Err(ColumnError::TooManyBlocks {
                blocks: blocks.len(),
            });
        }
        let at = |block: usize| move |invalid| ColumnError::InvalidBlock { block, invalid };
        let mut half_contact = Vec::with_capacity(blocks.len());
        let mut base_height = Vec::with_capacity(blocks.len());
        let mut inertia = Vec::with_capacity(blocks.len());
        let mut y = 0.0;
        for (k, b) in blocks.iter().enumerate() {
            positive("width", b.width).map_err(at(k))?;
            positive("height", b.height).map_err(at(k))?;
            positive("mass", b.mass).map_err(at(k))?;
            let i = b
                .inertia
                .unwrap_or(b.mass * (b.width * b.width + b.height * b.height) / 12.0);
            if b.inertia.is_none() && !i.is_finite() {
                return Err(ColumnError::TooLarge {
                    block: k,
                    quantity: format!(
                        "the inertia m (w² + h²) / 12 from mass = {:?}, width = {:?}, height = {:?}",
                        b.mass, b.width, b.height
                    ),
                });
            }
            positive("inertia", i).map_err(at(k))?;
            let widest = if k == 0 {
                b.width
            } else {
                b.width.min(blocks[k - 1].width)
            };
            let contact = b.contact_width.unwrap_or(widest);
            positive("contact_width", contact).map_err(at(k))?;
            if contact > widest * (1.0 + 1e-12) {
                return Err(at(k)(InvalidValue::new(
                    "contact_width",
                    contact,
                    "must not be wider than the blocks it joins",
                )));
            }
            half_contact.push(0.5 * contact);
            base_height.push(y);
            inertia.push(i);
            y += b.height;
            if !y.is_finite() {
                return Err(ColumnError::TooLarge {
                    block: k,
                    quantity: "the height of the column up to the top of this block".to_string(),
                });
            }
        }
        Ok(Column {
            blocks,
            half_contact,
            base_height,
            inertia,
        })
    }

    /// A column of `n` equal uniform rectangular blocks stacked to the given total height.
    pub fn uniform(
        n: usize,
        width: f64,
        total_height: f64,
        total_mass: f64,
    ) -> Result<Column, ColumnError> {
        let h = total_height / n as f64;
        let m = total_mass / n as f64;
        Column::new((0..n).map(|_| Block::rectangle(width, h, m)).collect())
    }

    /// Number of blocks, equal to the number of interfaces `n`.
    pub fn n_interfaces(&self) -> usize {
        self.blocks.len()
    }

    /// Number of rotational DOFs, `2n`.
    pub fn n_dofs(&self) -> usize {
        2 * self.blocks.len()
    }

    /// The blocks, bottom to top.
    pub fn blocks(&self) -> &[Block] {
        &self.blocks
    }

    /// Half contact width `b_k` of interface `k`.
    pub fn half_contact_width(&self, k: usize) -> f64 {
        self.half_contact[k]
    }

    /// Height of interface `k` in the straight column, `Σ_{j<k} h_j`.
    pub(crate) fn base_height(&self, k: usize) -> f64 {
        self.base_height[k]
    }

    /// Moment of inertia of block `k` about its centre.
    pub fn inertia(&self, k: usize) -> f64 {
        self.inertia[k]
    }

    /// Total height of the straight column.
    pub fn total_height(&self) -> f64 {
        self.blocks.iter().map(|b| b.height).sum()
    }

    /// Total mass.
    pub fn total_mass(&self) -> f64 {
        self.blocks.iter().map(|b| b.mass).sum()
    }

    /// Horizontal ground acceleration at which a straight column starts to rock (static):
    /// the smallest `a_g` that tips the part above some interface about one of its corners,
    /// `min_k g b_k / h_k` with `h_k` the height of the centre of mass of the part above interface
    /// `k` over that interface. Below it in absolute value, the column moves with the ground. For a
    /// single uniform block this is `a_p,min = g tan δ` (thesis Eq. 3).
    pub fn static_uplift_acceleration(&self, gravity: f64) -> f64 {
        let mut least = f64::INFINITY;
        for k in 0..self.n_interfaces() {
            let base = self.base_height[k];
            let (mut mass, mut moment) = (0.0, 0.0);
            let mut y = base;
            for b in &self.blocks[k..] {
                mass += b.mass;
                moment += b.mass * (y + 0.5 * b.height - base);
                y += b.height;
            }
            least = least.min(gravity * self.half_contact[k] / (moment / mass));
        }
        least
    }
}

#[cfg(test)]
mod tests;
