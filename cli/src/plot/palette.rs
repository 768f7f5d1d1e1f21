//! Colours and legend names of the members of a column (blocks, drums, joints), bottom to top.
//! Up to eight: the palette's colours, each named. More: a sequence from dark blue at the base
//! to yellow-green at the top (viridis without its palest end), every member its own shade, and
//! at most [`MAX_NAMED`] of them named, evenly spaced with the base and the top among them — the
//! palette repeated every eight (drum 0 and drum 8 the same blue) and thirty names were more
//! than a legend can show.

use super::{Rgb, COLORS};

/// Most members named in a legend.
pub const MAX_NAMED: usize = 7;

/// viridis at 0, 0.2, 0.4, 0.6, 0.8 and 0.9.
const STOPS: [Rgb; 6] = [
    (0x44, 0x01, 0x54),
    (0x41, 0x44, 0x87),
    (0x2a, 0x78, 0x8e),
    (0x22, 0xa8, 0x84),
    (0x7a, 0xd1, 0x51),
    (0xbd, 0xdf, 0x26),
];

/// The colour of member `k` of `n`.
pub fn member_color(k: usize, n: usize) -> Rgb {
    if n <= COLORS.len() {
        return COLORS[k % COLORS.len()];
    }
    let f = k as f64 / (n - 1) as f64 * (STOPS.len() - 1) as f64;
    let i = (f.floor() as usize).min(STOPS.len() - 2);
    let w = f - i as f64;
    let mix = |a: u8, b: u8| (f64::from(a) + w * (f64::from(b) - f64::from(a))).round() as u8;
    let (a, b) = (STOPS[i], STOPS[i + 1]);
    (mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// The legend name of member `k` of `n` called `what` (`"drum"`, …): `"drum 4"`, or empty (no
/// legend entry of its own) when `n` is large and `k` is not among the named ones.
pub fn member_name(what: &str, k: usize, n: usize) -> String {
    let named = n <= COLORS.len()
        || (0..MAX_NAMED).any(|i| k == (i * (n - 1) + (MAX_NAMED - 1) / 2) / (MAX_NAMED - 1));
    if named {
        format!("{what} {k}")
    } else {
        String::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn few_members_take_the_palette_and_many_a_sequence_of_their_own() {
        for (k, &c) in COLORS.iter().enumerate() {
            assert_eq!(member_color(k, 8), c);
            assert_eq!(member_name("drum", k, 8), format!("drum {k}"));
        }
        for n in [9, 30, 100] {
            let colors: Vec<Rgb> = (0..n).map(|k| member_color(k, n)).collect();
            let mut distinct = colors.clone();
            distinct.sort_unstable();
            distinct.dedup();
            assert_eq!(distinct.len(), n, "{n} members");
            assert_eq!((colors[0], colors[n - 1]), (STOPS[0], STOPS[5]));
            let named: Vec<usize> = (0..n)
                .filter(|&k| !member_name("drum", k, n).is_empty())
                .collect();
            assert_eq!(named.len(), MAX_NAMED, "{n}: {named:?}");
            assert_eq!((named[0], named[MAX_NAMED - 1]), (0, n - 1));
        }
    }
}
