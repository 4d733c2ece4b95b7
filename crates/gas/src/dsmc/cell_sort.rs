//! Sorting the spatial engine's particles into collision cells, in place.
//!
//! A stable counting sort: one key per particle (its cell), counts per cell, each
//! particle's place from the running counts, and the permutation applied in place by
//! following its cycles. Stable: the order within a cell is the order before, so the result
//! is exactly that of any stable sort (the merge sort this replaced, which took ~80 % of the
//! instructions of a step). In place: the only extra memory is 4 bytes per particle (the
//! places) and 4 per cell, where a scatter into a second array would double the 56 bytes
//! of a record.

use crate::prefetch::prefetch;
use rayon::prelude::*;

/// Links of a permutation's cycle fetched ahead of the one being moved.
const CYCLE_LOOKAHEAD: usize = 16;

/// Counting sort pays while the cells are at most this many per particle (its counts array
/// is O(cells)); beyond, a stable comparison sort.
const COUNTING_SORT_CELLS_PER_PARTICLE: u64 = 4;

/// The scratch arrays of the sort, kept between steps.
#[derive(Debug, Clone, Default)]
pub(crate) struct CellSorter {
    /// Per particle: its cell, then its place in the sorted order.
    places: Vec<u32>,
    /// Per cell: particles counted, then the next free place.
    counts: Vec<u32>,
}

impl CellSorter {
    /// Bytes held between steps.
    pub fn memory_bytes(&self) -> usize {
        (self.places.capacity() + self.counts.capacity()) * 4
    }

    /// Applies `update` to every item (in parallel), then sorts the items stably by `key`
    /// (a cell index below `cells`), and returns where each non-empty cell starts.
    pub fn update_and_sort<T: Copy + Send + Sync>(
        &mut self,
        items: &mut [T],
        cells: u64,
        update: impl Fn(&mut T) + Sync,
        key: impl Fn(&T) -> u64 + Sync,
    ) -> Vec<usize> {
        let n = items.len();
        let counting = cells <= COUNTING_SORT_CELLS_PER_PARTICLE * n as u64
            && cells <= u32::MAX as u64
            && n <= u32::MAX as usize;
        if !counting {
            items.par_iter_mut().for_each(&update);
            items.par_sort_by_key(&key);
            let items = &*items;
            return (0..n)
                .into_par_iter()
                .filter(|&i| i == 0 || key(&items[i]) != key(&items[i - 1]))
                .collect();
        }
        self.places.resize(n, 0);
        const CHUNK: usize = 4096;
        items
            .par_chunks_mut(CHUNK)
            .zip(self.places.par_chunks_mut(CHUNK))
            .for_each(|(items, places)| {
                for (item, place) in items.iter_mut().zip(places) {
                    update(item);
                    *place = key(item) as u32;
                }
            });
        // Counts per chunk of particles (one chunk per thread, if the counts stay below N):
        // the place of a particle is the start of its cell, plus the particles of that
        // cell in earlier chunks, plus those before it in its chunk: the stable order,
        // whatever the number of chunks.
        let cells = cells as usize;
        let threads = rayon::current_num_threads().max(1);
        let chunks = if cells.saturating_mul(threads) <= n {
            threads
        } else {
            1
        };
        let chunk = n.div_ceil(chunks).max(1);
        self.counts.clear();
        self.counts.resize(cells * chunks, 0);
        self.counts
            .par_chunks_mut(cells)
            .zip(self.places.par_chunks(chunk))
            .for_each(|(counts, keys)| {
                for &k in keys {
                    counts[k as usize] += 1;
                }
            });
        let mut starts = Vec::new();
        let mut at = 0u32;
        for cell in 0..cells {
            let first = at;
            for c in 0..chunks {
                let slot = &mut self.counts[c * cells + cell];
                let count = *slot;
                *slot = at;
                at += count;
            }
            if at > first {
                starts.push(first as usize);
            }
        }
        self.counts
            .par_chunks_mut(cells)
            .zip(self.places.par_chunks_mut(chunk))
            .for_each(|(next, places)| {
                for place in places.iter_mut() {
                    let slot = &mut next[*place as usize];
                    *place = *slot;
                    *slot += 1;
                }
            });
        permute_in_parallel(items, &mut self.places, threads);
        starts
    }
}

impl CellSorter {
    /// The keys of the items for [`CellSorter::sort_keyed_in_sequence`], to be filled by
    /// the caller (a cell index below its `cells` per item).
    pub fn keys(&mut self) -> &mut Vec<u32> {
        &mut self.places
    }

    /// Whether the counting sort of [`CellSorter::sort_keyed_in_sequence`] suits `n` items
    /// in `cells` cells (else [`CellSorter::update_and_sort`]).
    pub fn counts_cells(n: usize, cells: u64) -> bool {
        cells <= COUNTING_SORT_CELLS_PER_PARTICLE * n as u64
            && cells <= u32::MAX as u64
            && n <= u32::MAX as usize
    }

    /// Sorts `items` stably by the keys left in [`CellSorter::keys`] (one per item), the
    /// order kept being: the items at the indices `first` (in that order), then all the
    /// others as they stand, then those at `last` (in that order); returns where each
    /// non-empty cell starts. For a few items out of place (the arrivals and departures of
    /// a rank): the others keep their places, so the permutation stays near the identity.
    pub fn sort_keyed_in_sequence<T: Copy + Send>(
        &mut self,
        items: &mut [T],
        cells: u64,
        first: &[usize],
        last: &[usize],
    ) -> Vec<usize> {
        let n = items.len();
        assert_eq!(self.places.len(), n, "one key per item");
        let cells = cells as usize;
        self.counts.clear();
        self.counts.resize(cells, 0);
        for &k in &self.places {
            self.counts[k as usize] += 1;
        }
        let mut starts = Vec::new();
        let mut at = 0u32;
        for count in self.counts.iter_mut() {
            let here = *count;
            if here > 0 {
                starts.push(at as usize);
            }
            *count = at;
            at += here;
        }
        let (places, next) = (&mut self.places, &mut self.counts);
        let mut assign = |i: usize| {
            let slot = &mut next[places[i] as usize];
            places[i] = *slot;
            *slot += 1;
        };
        first.iter().for_each(|&i| assign(i));
        let mut special: Vec<usize> = first.iter().chain(last).copied().collect();
        special.sort_unstable();
        let mut skip = special.into_iter().peekable();
        for i in 0..n {
            if skip.peek() == Some(&i) {
                skip.next();
                continue;
            }
            assign(i);
        }
        last.iter().for_each(|&i| assign(i));
        let threads = rayon::current_num_threads().max(1);
        permute_in_parallel(items, &mut self.places, threads);
        starts
    }
}

/// Moves items[i] to items[places[i]] for every i (`places` a permutation of 0..n, left as
/// the identity) on `threads` threads. The positions are split into one region per thread;
/// first the few items whose place lies in another region are exchanged into it (serially:
/// after a step of a fifth of the mean free time almost every particle's place is in its
/// region), then every region is permuted in place on its own thread. The result is the
/// permutation's, whatever the number of threads.
fn permute_in_parallel<T: Copy + Send>(items: &mut [T], places: &mut [u32], threads: usize) {
    let n = items.len();
    let size = n.div_ceil(threads.max(1)).max(1);
    let regions = n.div_ceil(size);
    if regions <= 1 {
        return permute_in_place(items, places, 0);
    }
    let region_of = |place: u32| place as usize / size;
    // Per region, its positions holding an item that belongs to another region.
    let misplaced: Vec<Vec<u32>> = places
        .par_chunks(size)
        .enumerate()
        .map(|(r, chunk)| {
            let base = r * size;
            (0..chunk.len())
                .filter(|&i| region_of(chunk[i]) != r)
                .map(|i| (base + i) as u32)
                .collect()
        })
        .collect();
    // Each exchange puts one item into its region, into a position that held a misplaced
    // item (the next one of that region's list), and brings that item out.
    let mut next = vec![0usize; regions];
    for q in 0..regions {
        while next[q] < misplaced[q].len() {
            let p = misplaced[q][next[q]] as usize;
            let r = region_of(places[p]);
            if r == q {
                next[q] += 1;
                continue;
            }
            let v = misplaced[r][next[r]] as usize;
            items.swap(p, v);
            places.swap(p, v);
            next[r] += 1;
        }
    }
    items
        .par_chunks_mut(size)
        .zip(places.par_chunks_mut(size))
        .enumerate()
        .for_each(|(r, (items, places))| permute_in_place(items, places, r * size));
}

/// Moves items[i] to items[places[i] - base] for every i (`places` minus `base` a
/// permutation of 0..n, left as the identity plus `base`), following the permutation's
/// cycles: each item is read and written once.
///
/// A cycle is a chain of dependent loads through the items (56 MB at N = 1e6), each a
/// likely cache miss after a step; a second walker runs [`CYCLE_LOOKAHEAD`] links ahead
/// through `places` (4 bytes per item, mostly in cache), fetching the items the cycle will
/// reach, so that their misses overlap (it took ~60 % of a spatial step without).
fn permute_in_place<T: Copy>(items: &mut [T], places: &mut [u32], base: usize) {
    for i in 0..items.len() {
        let mut to = places[i] as usize - base;
        if to == i {
            continue;
        }
        // The walker reads only links the cycle has not yet reached (and so not reset);
        // it stops at the cycle's start.
        let mut ahead = to;
        for _ in 0..CYCLE_LOOKAHEAD {
            if ahead == i {
                break;
            }
            prefetch(&items[ahead..ahead + 1]);
            ahead = places[ahead] as usize - base;
        }
        let mut carried = items[i];
        while to != i {
            if ahead != i {
                prefetch(&items[ahead..ahead + 1]);
                ahead = places[ahead] as usize - base;
            }
            let displaced = items[to];
            let onward = places[to] as usize - base;
            items[to] = carried;
            places[to] = (to + base) as u32;
            carried = displaced;
            to = onward;
        }
        items[i] = carried;
        places[i] = (i + base) as u32;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The counting sort gives exactly the stable comparison sort's order and cell starts
    /// (many particles per cell, empty cells, the order within a cell kept), and so does
    /// the comparison sort it falls back to for many cells.
    #[test]
    fn counting_sort_is_the_stable_sort() {
        let mut state = 7u64;
        let items: Vec<(u64, u32)> = (0..5000)
            .map(|i| {
                state = state
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                ((state >> 33) % 700, i)
            })
            .collect();
        let key = |x: &(u64, u32)| x.0;
        let mut expected = items.clone();
        expected.sort_by_key(key);
        let expected_starts: Vec<usize> = (0..expected.len())
            .filter(|&i| i == 0 || expected[i].0 != expected[i - 1].0)
            .collect();
        let mut sorter = CellSorter::default();
        for cells in [700, 3000, 4 * 5000 + 1] {
            let mut sorted = items.clone();
            let starts = sorter.update_and_sort(&mut sorted, cells, |_| {}, key);
            assert_eq!(sorted, expected, "{cells} cells");
            assert_eq!(starts, expected_starts, "{cells} cells");
        }
        // The update is applied before the keys are taken.
        let mut shifted = items.clone();
        sorter.update_and_sort(&mut shifted, 700, |x| x.0 = (x.0 + 1) % 700, key);
        let mut want: Vec<(u64, u32)> = items.iter().map(|&(k, i)| ((k + 1) % 700, i)).collect();
        want.sort_by_key(key);
        assert_eq!(shifted, want);
    }

    /// The sort in a sequence: the stable sort of the items taken in that sequence.
    #[test]
    fn sort_in_sequence_is_the_stable_sort_of_the_sequence() {
        let items: Vec<(u64, u32)> = (0..3000u32).map(|i| ((i as u64 * 7919) % 101, i)).collect();
        let (first, last) = (vec![2999, 5, 17], vec![0, 1000, 2998]);
        let mut sequence: Vec<(u64, u32)> = first.iter().map(|&i| items[i]).collect();
        sequence.extend(
            (0..items.len())
                .filter(|i| !first.contains(i) && !last.contains(i))
                .map(|i| items[i]),
        );
        sequence.extend(last.iter().map(|&i| items[i]));
        sequence.sort_by_key(|x| x.0);
        let mut sorter = CellSorter::default();
        *sorter.keys() = items.iter().map(|x| x.0 as u32).collect();
        let mut sorted = items.clone();
        let starts = sorter.sort_keyed_in_sequence(&mut sorted, 101, &first, &last);
        assert_eq!(sorted, sequence);
        let want: Vec<usize> = (0..sorted.len())
            .filter(|&i| i == 0 || sorted[i].0 != sorted[i - 1].0)
            .collect();
        assert_eq!(starts, want);
    }

    /// The region-parallel permutation moves every item to its place, for any number of
    /// regions (more than items too), a random permutation (most items change region) and
    /// a near-identity one (a few change region, as after a DSMC step).
    #[test]
    fn parallel_permutation_is_the_permutation() {
        let mut state = 11u64;
        let mut random = |below: usize| {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 33) as usize % below
        };
        for n in [0, 1, 2, 5, 1000] {
            let mut shuffled: Vec<u32> = (0..n as u32).collect();
            for i in (1..n).rev() {
                shuffled.swap(i, random(i + 1));
            }
            let mut near: Vec<u32> = (0..n as u32).collect();
            for _ in 0..n / 20 {
                let (i, j) = (random(n), random(n));
                near.swap(i, j);
            }
            for places in [shuffled, near] {
                for threads in [1, 2, 3, 4, 7, 2000] {
                    let mut items: Vec<u64> = (0..n as u64).map(|i| 10 * i).collect();
                    let mut scratch = places.clone();
                    permute_in_parallel(&mut items, &mut scratch, threads);
                    for (i, &place) in places.iter().enumerate() {
                        assert_eq!(items[place as usize], 10 * i as u64, "{n} {threads}");
                    }
                    assert!(scratch.iter().enumerate().all(|(i, &p)| p as usize == i));
                }
            }
        }
    }
}
