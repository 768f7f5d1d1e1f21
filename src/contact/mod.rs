//! Columns of drums that rock, slide and fly: event-capturing time stepping (Moreau–Jean) with
//! Coulomb friction at the joints.
//!
//! The event-driven driver ([`crate::driver`]) follows the thesis: between events the column
//! moves in one configuration (each joint closed or rotating about a corner), and at every event
//! the opening or impact model chooses the next one. That is exact and cheap while events are few,
//! but a column of many squat drums meets accumulations of impacts (a joint chattering shut,
//! joints closing in cascade) that no event-driven scheme can step through, and joints that slide
//! or lift off, which the thesis's model stops at. This module is the standard method for many
//! contacts: every time step solves one frictional contact problem at velocity level
//! (Moreau 1988, Jean 1999; Acary & Brogliato, *Numerical Methods for Nonsmooth Dynamical
//! Systems*, 2008, §10.1), in natural coordinates (`x, y, θ` per drum).
//!
//! - [`drums`]: the column in natural coordinates, the joints' contact ends (the ends of the
//!   overlap of the two faces), gaps, slips and Jacobian rows.
//! - [`friction`]: the contact problem of one step or one impact, joint by joint (Signorini at the
//!   ends, Coulomb on the joint), solved exactly by an active set method on the block-tridiagonal
//!   Delassus matrix ([`active_set`]), Lemke's algorithm ([`lemke`]) and the nonsmooth
//!   Gauss–Seidel iteration ([`fallback`]) as the fallbacks.
//! - [`moreau`]: one time step; [`landing`]: impacts located inside it and the consecutive-impact
//!   law; [`projection`]: the positions projected back onto the contacts; [`rest`]: the step of a
//!   column at rest; [`accounts`]: the energy accounts and work counters; [`refine`]: the opt-in
//!   error control (a step whose energy error is too large redone as two halves);
//!   [`consistent`]: the opt-in removal of the located impacts' one-signed energy errors.
//! - [`simulation`]: a whole run: joint modes, events, stops, slips, energy; its options are
//!   [`options`], what it gives back (events, stops, energy, history, outcome) [`outcome`].
//! - [`auto`]: the automatic scheme: the event-driven driver where events are few, this scheme
//!   where they crowd, the state handed between them (`handover`).

pub mod accounts;
pub mod active_set;
pub mod auto;
mod blocks;
pub mod clusters;
pub mod consistent;
pub mod drums;
pub mod fallback;
pub mod friction;
pub(crate) mod handover;
pub mod landing;
pub mod lemke;
pub mod moreau;
pub mod options;
pub mod outcome;
pub mod projection;
pub mod refine;
pub mod rest;
pub mod simulation;
