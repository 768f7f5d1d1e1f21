//! A capped colonnade (SPEC §9): two columns of stacked blocks on the ground carrying a freely
//! supported beam — the frame of Makris & Vassiliou (EESD 2013) and of ancient trilithons. Chain
//! order: ground → left column (bottom to top) → beam → right column (top to bottom) → ground.
//! The left column's joints have `n = +y` (so `R` is the right corner, as in a column); the beam
//! to the right column and the right column's joints have `n = −y` (chain order runs down), so
//! there `R_k` is the corner on the left in world coordinates.

use crate::chain::{Body, Chain, Joint};
use crate::model::column::Block;
use crate::validate::{self, InvalidValue};

/// Two columns and a beam. The left column's axis is `x = 0`, the right one's `x = span`; both
/// columns must have the same height; the beam is centred between them and must reach over both
/// column tops.
#[derive(Clone, Debug, PartialEq)]
pub struct CappedColonnade {
    /// Left column, bottom to top.
    pub left: Vec<Block>,
    /// Right column, bottom to top.
    pub right: Vec<Block>,
    /// The beam: `width` is its length, `height` its depth; `contact_width` is not used (it bears
    /// on the full top face of each column).
    pub beam: Block,
    /// Distance between the column axes (m).
    pub span: f64,
}

fn inertia(b: &Block) -> f64 {
    b.inertia
        .unwrap_or(b.mass * (b.width * b.width + b.height * b.height) / 12.0)
}

/// A block's inertia when it is derived (`m (w² + h²) / 12`, none given) and overflows: the
/// block named with its dimensions, under [`super::TOO_LARGE`], not a derived `inertia = inf`.
fn check_derived_inertia(field: String, b: &Block) -> Result<(), InvalidValue> {
    if b.inertia.is_none() && !inertia(b).is_finite() {
        return Err(InvalidValue {
            field,
            value: format!(
                "{{width: {:?}, height: {:?}, mass: {:?}}}",
                b.width, b.height, b.mass
            ),
            rule: super::TOO_LARGE,
        });
    }
    Ok(())
}

impl CappedColonnade {
    /// The frame of Makris & Vassiliou: two equal monolithic columns `width × height` of mass
    /// `column_mass`, a beam `span + width` long (flush with the outer faces) of depth
    /// `beam_height` and mass `beam_mass`.
    pub fn frame(
        width: f64,
        height: f64,
        column_mass: f64,
        span: f64,
        beam_height: f64,
        beam_mass: f64,
    ) -> CappedColonnade {
        let column = vec![Block::rectangle(width, height, column_mass)];
        CappedColonnade {
            left: column.clone(),
            right: column,
            beam: Block::rectangle(span + width, beam_height, beam_mass),
            span,
        }
    }

    /// Checks the fields (each error names its field).
    pub fn validate(&self) -> Result<(), InvalidValue> {
        for (side, blocks) in [("left", &self.left), ("right", &self.right)] {
            if blocks.is_empty() {
                return Err(InvalidValue::new(
                    format!("colonnade.{side}"),
                    0,
                    "a column needs at least one block",
                ));
            }
            for (k, b) in blocks.iter().enumerate() {
                let f = |name: &str| format!("colonnade.{side}[{k}].{name}");
                validate::positive(f("width"), b.width)?;
                validate::positive(f("height"), b.height)?;
                validate::positive(f("mass"), b.mass)?;
                check_derived_inertia(format!("colonnade.{side}[{k}]"), b)?;
                validate::positive(f("inertia"), inertia(b))?;
                if let Some(c) = b.contact_width {
                    validate::positive(f("contact_width"), c)?;
                    let widest = if k == 0 {
                        b.width
                    } else {
                        b.width.min(blocks[k - 1].width)
                    };
                    if c > widest * (1.0 + 1e-12) {
                        return Err(InvalidValue::new(
                            f("contact_width"),
                            c,
                            "is wider than the blocks it joins",
                        ));
                    }
                }
            }
        }
        validate::positive("colonnade.beam.width", self.beam.width)?;
        validate::positive("colonnade.beam.height", self.beam.height)?;
        validate::positive("colonnade.beam.mass", self.beam.mass)?;
        check_derived_inertia("colonnade.beam".to_string(), &self.beam)?;
        validate::positive("colonnade.beam.inertia", inertia(&self.beam))?;
        validate::positive("colonnade.span", self.span)?;
        let (hl, hr) = (
            self.column_height(&self.left),
            self.column_height(&self.right),
        );
        if (hl - hr).abs() > 1e-9 * hl.max(hr) {
            return Err(InvalidValue::new(
                "colonnade.right",
                hr,
                "the right column must be as tall as the left one",
            ));
        }
        let (wl, wr) = (top(&self.left).width, top(&self.right).width);
        if 0.5 * (wl + wr) >= self.span {
            return Err(InvalidValue::new(
                "colonnade.span",
                self.span,
                "the columns overlap: the span must exceed the mean of their top widths",
            ));
        }
        let reach = 0.5 * self.beam.width;
        if reach < 0.5 * self.span + 0.5 * wl.max(wr) * (1.0 - 1e-12) {
            return Err(InvalidValue::new(
                "colonnade.beam.width",
                self.beam.width,
                "the beam must cover both column tops (at least span + top width)",
            ));
        }
        Ok(())
    }

    fn column_height(&self, blocks: &[Block]) -> f64 {
        blocks.iter().map(|b| b.height).sum()
    }

    /// Height of the columns.
    pub fn height(&self) -> f64 {
        self.column_height(&self.left)
    }

    /// The loop: left blocks, beam, right blocks (top to bottom); `n_left + n_right + 2` joints.
    pub fn chain(&self) -> Result<Chain, InvalidValue> {
        self.validate()?;
        let h = self.height();
        let contact = |blocks: &[Block], k: usize| -> f64 {
            let b = &blocks[k];
            b.contact_width.unwrap_or(if k == 0 {
                b.width
            } else {
                b.width.min(blocks[k - 1].width)
            })
        };
        let levels = |blocks: &[Block]| -> Vec<f64> {
            let mut y = 0.0;
            blocks
                .iter()
                .map(|b| {
                    let base = y;
                    y += b.height;
                    base
                })
                .collect()
        };
        let (yl, yr) = (levels(&self.left), levels(&self.right));
        let mut bodies = Vec::new();
        let mut joints = Vec::new();
        let up = [0.0, 1.0];
        let down = [0.0, -1.0];
        for (k, b) in self.left.iter().enumerate() {
            joints.push(Joint {
                centre: [0.0, yl[k]],
                normal: up,
                half_width: 0.5 * contact(&self.left, k),
            });
            bodies.push(Body {
                mass: b.mass,
                inertia: inertia(b),
                centre: [0.0, yl[k] + 0.5 * b.height],
            });
        }
        joints.push(Joint {
            centre: [0.0, h],
            normal: up,
            half_width: 0.5 * top(&self.left).width.min(self.beam.width),
        });
        bodies.push(Body {
            mass: self.beam.mass,
            inertia: inertia(&self.beam),
            centre: [0.5 * self.span, h + 0.5 * self.beam.height],
        });
        joints.push(Joint {
            centre: [self.span, h],
            normal: down,
            half_width: 0.5 * top(&self.right).width.min(self.beam.width),
        });
        let nr = self.right.len();
        for k in (0..nr).rev() {
            let b = &self.right[k];
            bodies.push(Body {
                mass: b.mass,
                inertia: inertia(b),
                centre: [self.span, yr[k] + 0.5 * b.height],
            });
            // The joint under block k: between it and block k − 1 (or the ground).
            joints.push(Joint {
                centre: [self.span, yr[k]],
                normal: down,
                half_width: 0.5 * contact(&self.right, k),
            });
        }
        Chain::new(bodies, joints)
    }
}

fn top(blocks: &[Block]) -> &Block {
    blocks.last().expect("validated: a column has blocks")
}
