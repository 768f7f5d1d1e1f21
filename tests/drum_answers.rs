//! The drum scheme's answers, bit for bit, before and after its speed-ups (issue 11,
//! docs/multidrum.md "Performance"): ten 1 × 1 m drums (μ = 0.5, sliding and flight) through
//! 30 s of Northridge MUL009 at 4 m/s² (skipped without `../shared`), five 1 × 2 m drums through
//! 20 s of the bundled synthetic record at 4 m/s² with the two-impact law, and three 1 × 1.5 m
//! drums at μ = 0.3 (sliding) under the synthetic record at 6 m/s². The expected values were printed by
//! this test at commit 94edc4c (before the speed-ups); an optimisation that reorders arithmetic
//! shows up here as a changed bit.

use std::path::Path;

use rocking::contact::simulation::{simulate, DrumOptions, DrumOutcome};
use rocking::ground::excitation::Excitation;
use rocking::ground::records::{read_at2, synthetic_record, Record, SYNTHETIC_SEED};
use rocking::model::column::{Block, Column};

fn run(n: usize, w: f64, h: f64, rec: Record, mu: f64, duration: f64, impacts: u32) -> DrumOutcome {
    let column = Column::new(vec![Block::rectangle(w, h, 2500.0 * w * h); n]).unwrap();
    let motion = Excitation::record(rec).unwrap();
    let opts = DrumOptions::quiet(duration, mu, impacts);
    simulate(&column, &motion, &opts, None).unwrap()
}

/// Every answer of a run as one line of text (shortest round-trip form of every float).
fn answers(o: &DrumOutcome) -> String {
    let e = &o.energy;
    let a = &e.accounts;
    format!(
        "stop {:?} t_end {:?} peak_rotation {:?} peak_slip {:?} residual_slip {:?} top {:?} \
         events {:?} modes {:?} energy [{:?}, {:?}, {:?}, {:?}, {:?}, {:?}, {:?}]",
        o.stop,
        o.t_end,
        o.peak_rotation,
        o.peak_slip,
        o.residual_slip,
        o.peak_top_displacement,
        o.event_counts,
        o.modes_end,
        e.potential_change,
        e.kinetic_change,
        a.ground_work,
        a.impact,
        a.friction,
        a.persistent_contact,
        a.projection,
    )
}

fn check(name: &str, got: &str, expected: &str) {
    assert_eq!(got, expected, "{name}: the answers changed");
}

#[test]
fn synthetic_columns_keep_their_answers() {
    let rec4 = synthetic_record(SYNTHETIC_SEED, 20.0, 0.01, 4.0).unwrap();
    let five = run(5, 1.0, 2.0, rec4, 0.5, 20.0, 2);
    let rec6 = synthetic_record(SYNTHETIC_SEED, 20.0, 0.01, 6.0).unwrap();
    let three = run(3, 1.0, 1.5, rec6, 0.3, 20.0, 1);
    check("five 1 x 2 drums", &answers(&five), FIVE);
    check("three 1 x 1.5 drums", &answers(&three), THREE);
}

#[test]
fn ten_drums_under_mul009_keep_their_answers() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/records/fema-p695/farfield/RSN953_NORTHR_MUL009.AT2");
    let Ok(rec) = read_at2(&path) else {
        eprintln!("skipped: {} not found", path.display());
        return;
    };
    let ten = run(10, 1.0, 1.0, rec.scaled_to_pga(4.0).unwrap(), 0.5, 30.0, 1);
    check("ten 1 x 1 drums, MUL009", &answers(&ten), TEN);
}

const FIVE: &str =
    "stop Duration t_end 20.0 peak_rotation [0.03534854584867709, 0.035348545848677144, \
    0.03534854584867779, 0.03534854584867779, 0.0353485458486776] peak_slip \
    [0.0004390139869823173, 1.3429746733295556e-5, 2.7174494637793867e-5, \
    1.0636418695753047e-5, 3.6613819389075264e-5] residual_slip [-0.00040751427984303534, \
    2.0905488533617955e-6, 1.825961412788013e-5, 4.298834353821945e-6, 3.367726186476183e-5] \
    top 0.318732257684115 events [180, 607, 72, 72, 14, 14, 0] modes [RockingLeft, Closed, \
    Closed, Closed, Closed] energy [71.70479175388108, 1915.6194052746227, \
    2843.206202498597, 811.3089258290203, 47.5357366555612, -2.2738722351131755, \
    -0.688784773495528]";
const THREE: &str =
    "stop Duration t_end 20.0 peak_rotation [0.0991685479054437, 0.09916854790544366, \
    0.09916854790544365] peak_slip [8.140644701670752e-7, 1.598756375564836e-6, \
    0.07106252136137442] residual_slip [7.984798887639144e-7, 1.5519887009429745e-6, \
    0.05155501944910845] top 0.42503311610015454 events [1, 35, 48, 48, 0, 0, 0] modes \
    [RockingLeft, Closed, Closed] energy [1917.678354213892, 249.57794773050296, \
    10828.15924952077, 6907.547697638035, 1753.5218504046782, 0.04990702061318371, \
    -0.21650748737375466]";
const TEN: &str =
    "stop Duration t_end 30.0 peak_rotation [0.04797046767696699, 0.05101437077632465, \
    0.05101437077632501, 0.05101437077632501, 0.05101437077632445, 0.05101437077632446, \
    0.05101437077632445, 0.05101437077632445, 0.0510143707763232, 0.0510143707763232] \
    peak_slip [0.002021942455438408, 0.0007066098800390108, 7.848467493326572e-5, \
    0.0001729271906545926, 0.0003547751504611174, 0.0007303109679281938, \
    0.0007777224066356503, 0.0015099234530080996, 0.0010880190970440906, \
    0.00027046040812400696] residual_slip [0.001220364503412008, 0.00029990819120334633, \
    6.071787398709283e-5, 0.00013593587725108103, 0.00020995924275268862, \
    0.0004919903384237312, 0.00044909796166681115, 0.0011572511876412062, \
    0.0007853192934043629, -7.282897300914248e-5] top 0.48497703929485775 events [1005, \
    1516, 414, 414, 0, 0, 0] modes [RockingLeft, Closed, Closed, Closed, Closed, Closed, \
    Closed, Closed, Closed, Closed] energy [1392.1556139881445, 970.9503116118487, \
    8381.676534473416, 5005.929065117932, 989.7808911547398, 24.321337917203763, \
    -1.4606853173626964]";
