//! The capped colonnade through the loop driver: Makris & Vassiliou (2013).

use super::*;

/// The capped colonnade through the loop driver: a frame of two 1 × 5 m columns (tan α = 0.2)
/// and a beam of the two columns' mass (γ = m_beam / (2 m_column) = 0.5), pushed over
/// `g tan α` by a half-sine, rocks as a four-hinge mechanism whose four hinges close together
/// and reopen about the opposite corners; every impact keeps the share of kinetic energy of
/// Makris & Vassiliou's (2013) frame, `r = [(1 − 3/2 sin²α + 3γ cos 2α)/(1 + 3γ)]²`
/// (0.866331 here; a lone column keeps Housner's `(1 − 3/2 sin²α)² = 0.8880`). Measured: equal
/// to 1e-15.
#[test]
fn colonnade_impacts_keep_makris_vassiliou_restitution() {
    use rocking::chain::colonnade::CappedColonnade;
    let frame = CappedColonnade::frame(1.0, 5.0, 12500.0, 4.0, 0.5, 12500.0);
    let chain = frame.chain().unwrap();
    let motion = FnMotion(|t| ground(t, -3.0, 0.5), 0.5);
    let out = from_rest(&chain, &motion, 4.0).unwrap();
    let alpha = (0.2f64).atan();
    let gamma = 0.5;
    let r = ((1.0 - 1.5 * alpha.sin().powi(2) + 3.0 * gamma * (2.0 * alpha).cos())
        / (1.0 + 3.0 * gamma))
        .powi(2);
    let mut impacts = 0;
    for e in &out.events {
        if let LoopEventKind::Closing {
            joints,
            kinetic_before,
            kinetic_after,
        } = &e.kind
        {
            assert_eq!(joints, &vec![0, 1, 2, 3]);
            let ratio = kinetic_after / kinetic_before;
            assert!((ratio - r).abs() < 1e-12, "{ratio} vs {r}");
            // The opposite corners after.
            assert_eq!(e.statuses.iter().filter(|&&s| s != 0).count(), 4);
            impacts += 1;
        }
    }
    assert!(impacts >= 5 && !out.collapsed, "{impacts}");
}

/// Makris & Vassiliou's overturning check for the capped colonnade: the frame of
/// `colonnade_impacts_keep_makris_vassiliou_restitution` (tan α = 0.2, γ = 0.5, `p̂² = p² (1 + 2γ)
/// / (1 + 3γ)`) against a single column of the same α and of the size that gives `p = p̂`
/// (`R̂ = R (1 + 3γ) / (1 + 2γ)`) through the column driver, under half-sines of frequency
/// `ω_p = π / t_p`: the smallest amplitude on a grid of 0.05 g tan α that overturns each (frame:
/// the loop driver's collapse, the one-DOF criterion (b), equivalent to the column's centre
/// passing its pivot). Before the first impact the two obey the same equation; after it they
/// differ by their restitutions (0.8663 against Housner's 0.8880). Prints the table of
/// docs/arches.md.
#[test]
#[ignore]
fn colonnade_overturning_against_single_column() {
    let fc = FrameAndColumn::new();
    let (chain, r_hat, p_hat, a_min) = (&fc.chain, fc.r_hat, fc.p_hat, fc.a_min);
    println!("p̂ = {p_hat:.6} rad/s, R̂ = {r_hat:.6} m");
    println!("| ω_p/p̂ | frame: a_p/(g tan α) | single column p = p̂ |");
    for ratio in [1.0, 2.0, 3.0, 4.0, 6.0] {
        let tp = PI / (ratio * p_hat);
        let duration = tp + 4.0;
        let mut first = [None, None];
        for i in 0..=140 {
            let level = 1.0 + 0.05 * i as f64;
            let amp = -level * a_min;
            let motion = FnMotion(move |t| ground(t, amp, tp), tp);
            if first[0].is_none() {
                let out = from_rest(chain, &motion, duration).unwrap();
                if out.collapsed {
                    first[0] = Some(level);
                }
            }
            if first[1].is_none() && column_run(&fc.column, &motion, duration).overturned {
                first[1] = Some(level);
            }
            if first.iter().all(|f| f.is_some()) {
                break;
            }
        }
        let show = |f: Option<f64>| f.map_or("> 8".to_string(), |v| format!("{v:.2}"));
        println!("| {ratio} | {} | {} |", show(first[0]), show(first[1]));
    }
}

/// The capped colonnade's whole overturning curve against Makris & Vassiliou's single column
/// (the frame and the column of `colonnade_overturning_against_single_column`): for each
/// `ω_p/p̂`, every amplitude of a grid of 0.05 g tan α from 1 to 8 that overturns, as
/// intervals, for the frame (loop driver) and the single column with `p = p̂` (column driver),
/// and the grid points where the two verdicts differ. `PULSE=sine`: one full sine cycle of
/// `ω_p` (Makris & Vassiliou's one-sine pulse, whose overturning region has the island of
/// overturning after an impact) instead of the half-sine. Prints the tables of
/// docs/arches.md §3.
#[test]
#[ignore]
fn colonnade_overturning_curve() {
    let sine = std::env::var("PULSE").is_ok_and(|p| p == "sine");
    let fc = FrameAndColumn::new();
    let (chain, p_hat, a_min) = (&fc.chain, fc.p_hat, fc.a_min);
    let ranges = |v: &[bool], levels: &[f64]| -> String {
        let mut out = Vec::new();
        let mut i = 0;
        while i < v.len() {
            if v[i] {
                let j = (i..v.len()).take_while(|&k| v[k]).last().unwrap();
                out.push(format!("{:.2}–{:.2}", levels[i], levels[j]));
                i = j + 1;
            } else {
                i += 1;
            }
        }
        out.join(", ")
    };
    let levels: Vec<f64> = (0..=140).map(|i| 1.0 + 0.05 * i as f64).collect();
    println!(
        "| ω_p/p̂ | frame overturns at a_p/(g tan α) (impacts before the lowest) | single column \
         p = p̂ | differ at |"
    );
    for ratio in [1.0, 2.0, 3.0, 4.0, 6.0] {
        let tp = PI / (ratio * p_hat);
        let length = if sine { 2.0 * tp } else { tp };
        let duration = length + 4.0;
        let (mut frame_over, mut column_over) = (Vec::new(), Vec::new());
        let mut first_impacts = [0usize; 2];
        for &level in &levels {
            let amp = -level * a_min;
            let motion = FnMotion(
                move |t: f64| {
                    if t < length {
                        amp * (PI * t / tp).sin()
                    } else {
                        0.0
                    }
                },
                length,
            );
            let out = from_rest(chain, &motion, duration).unwrap();
            let closings = out
                .events
                .iter()
                .filter(|e| matches!(e.kind, LoopEventKind::Closing { .. }))
                .count();
            frame_over.push(out.collapsed);
            let single = column_run(&fc.column, &motion, duration);
            // Impacts before the lowest overturning amplitude of each: 0 is the mode without
            // impact, more is overturning after impacts.
            if out.collapsed && !frame_over[..frame_over.len() - 1].contains(&true) {
                first_impacts[0] = closings;
            }
            if single.overturned && !column_over.contains(&true) {
                first_impacts[1] = single.impacts;
            }
            column_over.push(single.overturned);
        }
        let differ: Vec<String> = levels
            .iter()
            .zip(frame_over.iter().zip(&column_over))
            .filter(|(_, (a, b))| a != b)
            .map(|(l, (a, _))| format!("{l:.2}{}", if *a { "f" } else { "c" }))
            .collect();
        println!(
            "| {ratio} | {} ({} impacts) | {} ({} impacts) | {} |",
            ranges(&frame_over, &levels),
            first_impacts[0],
            ranges(&column_over, &levels),
            first_impacts[1],
            differ.join(" ")
        );
    }
}

/// The frame of `colonnade_impacts_keep_makris_vassiliou_restitution` (two 1 × 5 m columns of
/// 12.5 t, tan α = 0.2, γ = m_beam / (2 m_column) = 0.5) and Makris & Vassiliou's single column of
/// the same α with `p = p̂` (`R̂ = R (1 + 3γ) / (1 + 2γ)`), for the overturning tables below.
struct FrameAndColumn {
    chain: rocking::chain::Chain,
    column: rocking::model::column::Column,
    r_hat: f64,
    p_hat: f64,
    /// `g tan α`.
    a_min: f64,
}

impl FrameAndColumn {
    fn new() -> FrameAndColumn {
        use rocking::chain::colonnade::CappedColonnade;
        use rocking::model::column::{Block, Column};
        let (w, h, m) = (1.0, 5.0, 12500.0);
        let gamma = 0.5;
        let frame = CappedColonnade::frame(w, h, m, 4.0, 0.5, 2.0 * gamma * m);
        let alpha = (w / h).atan();
        let r = 0.5 * (w * w + h * h).sqrt();
        let r_hat = r * (1.0 + 3.0 * gamma) / (1.0 + 2.0 * gamma);
        FrameAndColumn {
            chain: frame.chain().unwrap(),
            column: Column::new(vec![Block::rectangle(
                2.0 * r_hat * alpha.sin(),
                2.0 * r_hat * alpha.cos(),
                m,
            )])
            .unwrap(),
            r_hat,
            p_hat: (3.0 * GRAVITY / (4.0 * r_hat)).sqrt(),
            a_min: GRAVITY * alpha.tan(),
        }
    }
}

/// The single column through the column driver at dt = 1 ms for `duration`.
fn column_run(
    column: &rocking::model::column::Column,
    motion: &dyn rocking::ground::GroundMotion,
    duration: f64,
) -> rocking::driver::Outcome {
    use rocking::driver::{simulate, SimulationOptions, SteppingOptions, StoppingOptions};
    let opts = SimulationOptions {
        stepping: SteppingOptions {
            dt: 1e-3,
            ..SteppingOptions::default()
        },
        stopping: StoppingOptions {
            duration,
            ..StoppingOptions::default()
        },
        ..SimulationOptions::default()
    };
    simulate(column, motion, &opts, None).unwrap()
}
