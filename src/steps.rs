//! Runs of contour points as chains of 8-connected steps, and maps keyed by them: the memos
//! of the greedy's pieces and of the exact polygon's segments, which look a run up one step
//! at a time.
//!
//! A key packs up to [`MAX_STEPS`] steps of 3 bits, their count and an end flag in a `u64`.
//! Most lookups miss (a glyph's pieces and segments hardly repeat), so a map also keeps a
//! 4096-bit filter of its keys' hashes, which answers most misses without a hash-map
//! lookup while the map is small (a glyph's few hundred keys; on noise, where it fills,
//! lookups hit often).

use crate::pixel::Pixel;
use rustc_hash::FxHashMap;

/// Most steps of a key.
pub(crate) const MAX_STEPS: usize = 19;

/// Bit of a key where the number of steps starts.
const COUNT_SHIFT: u32 = 3 * MAX_STEPS as u32;

/// Bit of a key that marks a run that reached the end of what it could take.
const END_BIT: u64 = 1 << (COUNT_SHIFT + 5);

/// The 3-bit code of the step from `a` to `b` (its [`Pixel::direction_to`]); `None` unless
/// they are 8-neighbours.
pub(crate) fn step(a: Pixel, b: Pixel) -> Option<u64> {
    a.direction_to(b).map(u64::from)
}

/// The key of `count` steps (`≤ MAX_STEPS`) whose codes are `bits` (the first in the
/// lowest three bits), with the end flag.
pub(crate) fn key(bits: u64, count: usize, end: bool) -> u64 {
    debug_assert!(count <= MAX_STEPS);
    let k = bits | (count as u64) << COUNT_SHIFT;
    if end {
        k | END_BIT
    } else {
        k
    }
}

/// The key of the steps between consecutive points of `run` (at most `MAX_STEPS + 1`
/// points), with the end flag. Returns None if a step is not between 8-neighbours.
pub(crate) fn key_of(run: impl Iterator<Item = Pixel>, end: bool) -> Option<u64> {
    let mut bits = 0;
    let mut count = 0;
    let mut prev: Option<Pixel> = None;
    for p in run {
        if let Some(q) = prev {
            if count == MAX_STEPS {
                return None;
            }
            bits |= step(q, p)? << (3 * count);
            count += 1;
        }
        prev = Some(p);
    }
    Some(key(bits, count, end))
}

/// Words of a [`StepMap`]'s filter.
const FILTER_WORDS: usize = 64;

/// A map from step keys, cleared when it holds `capacity` entries (its memory stays
/// bounded), with a filter that rules out most keys it does not hold.
#[derive(Debug)]
pub(crate) struct StepMap<V> {
    map: FxHashMap<u64, V>,
    filter: [u64; FILTER_WORDS],
    capacity: usize,
    /// Most steps of a key held.
    longest: usize,
}

/// The filter's word and bit of `key`.
fn slot(key: u64) -> (usize, u64) {
    let h = key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 52;
    ((h >> 6) as usize, 1 << (h & 63))
}

impl<V> StepMap<V> {
    /// An empty map of at most `capacity` entries.
    pub(crate) fn new(capacity: usize) -> StepMap<V> {
        StepMap {
            map: FxHashMap::default(),
            filter: [0; FILTER_WORDS],
            capacity,
            longest: 0,
        }
    }

    /// True when it holds nothing.
    #[cfg(test)]
    pub(crate) fn is_empty(&self) -> bool {
        self.map.is_empty()
    }

    /// The most steps of a key it holds (0 when empty): longer runs need not be looked up.
    pub(crate) fn longest(&self) -> usize {
        self.longest
    }

    /// The value of `key`.
    pub(crate) fn get(&self, key: u64) -> Option<&V> {
        let (w, b) = slot(key);
        if self.filter[w] & b == 0 {
            return None;
        }
        self.map.get(&key)
    }

    /// Sets the value of `key`, forgetting every other first when full.
    pub(crate) fn insert(&mut self, key: u64, value: V) {
        if self.map.len() >= self.capacity {
            self.clear();
        }
        let (w, b) = slot(key);
        self.filter[w] |= b;
        self.longest = self.longest.max(((key >> COUNT_SHIFT) & 31) as usize);
        self.map.insert(key, value);
    }

    /// Forgets everything.
    pub(crate) fn clear(&mut self) {
        self.map.clear();
        self.filter = [0; FILTER_WORDS];
        self.longest = 0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_are_the_eight_neighbours() {
        let o = Pixel::new(5, 5);
        let mut codes: Vec<u64> = (-1..=1)
            .flat_map(|dy| (-1..=1).map(move |dx| (dx, dy)))
            .filter_map(|(dx, dy)| step(o, Pixel::new(5 + dx, 5 + dy)))
            .collect();
        codes.sort_unstable();
        assert_eq!(codes, (0..8).collect::<Vec<_>>());
        assert_eq!(step(o, Pixel::new(7, 5)), None);
    }

    #[test]
    fn keys_tell_runs_apart() {
        let run = |v: &[(i32, i32)]| v.iter().map(|&(x, y)| Pixel::new(x, y)).collect::<Vec<_>>();
        let a = run(&[(0, 0), (1, 0), (2, 1)]);
        let b = run(&[(7, 7), (8, 7), (9, 8)]);
        let c = run(&[(0, 0), (1, 0)]);
        let k = |r: &[Pixel], end| key_of(r.iter().copied(), end).unwrap();
        assert_eq!(k(&a, false), k(&b, false));
        assert_ne!(k(&a, false), k(&a, true));
        // A run and its prefix differ by their counts.
        assert_ne!(k(&a, false) & !(7 << 3), k(&c, false));
        assert_eq!(key_of(run(&[(0, 0), (2, 0)]).into_iter(), false), None);
    }

    #[test]
    fn a_map_finds_what_it_holds_and_stays_bounded() {
        let mut m = StepMap::new(100);
        for k in 0..250u64 {
            m.insert(key(k, 3, k % 2 == 0), k);
            assert_eq!(m.get(key(k, 3, k % 2 == 0)), Some(&k));
        }
        assert_eq!(m.longest(), 3);
        assert!(m.map.len() <= 100);
        // Cleared at 100 and 200: what came before is gone, filter and all.
        assert_eq!(m.get(key(10, 3, true)), None);
        m.clear();
        assert!(m.is_empty() && m.filter.iter().all(|&w| w == 0) && m.longest() == 0);
    }
}
