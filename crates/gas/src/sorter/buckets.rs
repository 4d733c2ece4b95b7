//! A calendar queue ("buckets") sorter of the event-driven engine (after G. Paul, J. Comput. Phys. 221, 615
//! (2007)): one entry per particle, as the heap of [`super::heap`], but O(1) per update.
//!
//! Time is cut into `buckets` intervals of width `width` starting at bucket `first`;
//! every entry due before the end of the current bucket sits in a small binary heap, every
//! other entry in the unsorted list of its bucket, or in an overflow list if it is beyond
//! the last bucket. An update unlinks the particle from wherever it is (O(1) for a list,
//! O(log m) for the small heap of m entries) and links it in again. When the current
//! bucket is exhausted the next non-empty one is moved into the heap; after a full cycle
//! of buckets the overflow is redistributed, and the bucket width re-tuned from the mean
//! delay of the pending events.

const NONE: u32 = u32::MAX;
/// Mean number of events per bucket the width is tuned for.
const EVENTS_PER_BUCKET: f64 = 2.0;
/// A small heap larger than this means the buckets are too wide: re-tune (at most once
/// per N updates, which keeps the O(N) rebuild O(1) per update).
const LARGE_HEAP: usize = 256;
/// `place` of an entry in the small heap (its slot is in `heap_slot`).
const IN_HEAP: u32 = u32::MAX - 1;

/// Per-particle record: event time and its links in a bucket list.
#[derive(Debug, Clone, Copy)]
struct Record {
    time: f64,
    prev: u32,
    next: u32,
    /// Bucket index, `overflow` index (= number of buckets), or [`IN_HEAP`].
    place: u32,
    /// Position in the small heap when `place == IN_HEAP`.
    heap_slot: u32,
}

/// The calendar queue.
#[derive(Debug, Clone)]
pub struct BucketSorter {
    records: Vec<Record>,
    /// First particle of each bucket list; the last entry is the overflow list.
    heads: Vec<u32>,
    /// The small heap of (time, particle) of the entries due in the current bucket.
    heap: Vec<(f64, u32)>,
    /// Width of a bucket.
    width: f64,
    /// Absolute number of the current bucket (time / width, floored).
    current: u64,
    /// Absolute bucket number at which the cycle of buckets ends (overflow is then
    /// redistributed).
    cycle_end: u64,
    /// Updates since the last full rebuild.
    updates: usize,
}

impl BucketSorter {
    /// All `n` particles at time +infinity.
    pub fn new(n: usize) -> Self {
        let buckets = n.clamp(16, 1 << 26);
        let mut q = BucketSorter {
            records: vec![
                Record {
                    time: f64::INFINITY,
                    prev: NONE,
                    next: NONE,
                    place: NONE,
                    heap_slot: 0,
                };
                n
            ],
            heads: vec![NONE; buckets + 1],
            heap: Vec::new(),
            width: 1.0,
            current: 0,
            cycle_end: buckets as u64,
            updates: 0,
        };
        for i in 0..n {
            q.link(i, buckets as u32);
        }
        q
    }

    fn buckets(&self) -> usize {
        self.heads.len() - 1
    }

    /// Bytes held by the queue.
    pub fn memory_bytes(&self) -> usize {
        self.records.capacity() * std::mem::size_of::<Record>()
            + self.heads.capacity() * 4
            + self.heap.capacity() * std::mem::size_of::<(f64, u32)>()
    }

    pub fn time_of(&self, i: usize) -> f64 {
        self.records[i].time
    }

    /// The particle with the earliest event and its time (None if there are no particles).
    #[inline]
    pub fn peek(&mut self) -> Option<(usize, f64)> {
        if self.heap.len() > LARGE_HEAP && self.updates > self.records.len() {
            self.rebuild();
        }
        if self.heap.is_empty() {
            self.refill();
        }
        match self.heap.first() {
            Some(&(t, i)) => Some((i as usize, t)),
            // Only infinite times remain (or nothing at all).
            None => (!self.records.is_empty()).then_some((0, f64::INFINITY)),
        }
    }

    /// Sets the event time of particle i.
    #[inline]
    pub fn update(&mut self, i: usize, t: f64) {
        match self.records[i].place {
            IN_HEAP => self.heap_remove(self.records[i].heap_slot as usize),
            place => self.unlink(i, place),
        }
        self.records[i].time = t;
        self.file(i);
        self.updates += 1;
    }

    /// Moves every entry to the overflow list and starts a new cycle (re-tuning the width).
    fn rebuild(&mut self) {
        self.updates = 0;
        let overflow = self.buckets() as u32;
        for place in 0..self.buckets() {
            let mut j = std::mem::replace(&mut self.heads[place], NONE);
            while j != NONE {
                let next = self.records[j as usize].next;
                self.link(j as usize, overflow);
                j = next;
            }
        }
        for (_, i) in std::mem::take(&mut self.heap) {
            self.link(i as usize, overflow);
        }
        self.new_cycle();
    }

    /// The absolute bucket number of time t (saturating; +inf gives u64::MAX).
    #[inline]
    fn bucket_of(&self, t: f64) -> u64 {
        let b = t / self.width;
        if b >= 0.0 {
            b as u64
        } else {
            0
        }
    }

    /// Puts particle i (with its time set) where it belongs.
    #[inline]
    fn file(&mut self, i: usize) {
        let b = self.bucket_of(self.records[i].time);
        if b <= self.current {
            self.heap_push(i);
        } else if b < self.cycle_end {
            self.link(i, (b % self.buckets() as u64) as u32);
        } else {
            self.link(i, self.buckets() as u32);
        }
    }

    fn link(&mut self, i: usize, place: u32) {
        let head = self.heads[place as usize];
        if head != NONE {
            self.records[head as usize].prev = i as u32;
        }
        let r = &mut self.records[i];
        r.prev = NONE;
        r.next = head;
        r.place = place;
        self.heads[place as usize] = i as u32;
    }

    fn unlink(&mut self, i: usize, place: u32) {
        let Record { prev, next, .. } = self.records[i];
        if prev != NONE {
            self.records[prev as usize].next = next;
        } else {
            self.heads[place as usize] = next;
        }
        if next != NONE {
            self.records[next as usize].prev = prev;
        }
    }

    /// Moves the next non-empty bucket into the heap (redistributing the overflow at the
    /// end of each cycle); leaves the heap empty only if every time is infinite.
    fn refill(&mut self) {
        loop {
            self.current += 1;
            if self.current >= self.cycle_end {
                if !self.new_cycle() || !self.heap.is_empty() {
                    return;
                }
                continue;
            }
            let bucket = (self.current % self.buckets() as u64) as usize;
            let mut j = self.heads[bucket];
            if j == NONE {
                continue;
            }
            self.heads[bucket] = NONE;
            while j != NONE {
                let next = self.records[j as usize].next;
                self.heap_push(j as usize);
                j = next;
            }
            return;
        }
    }

    /// Starts a new cycle at the earliest pending time with a bucket width re-tuned so
    /// that a cycle spans a few mean delays; false if every pending time is infinite.
    fn new_cycle(&mut self) -> bool {
        // At the end of a cycle every bucket list is empty: all entries are in overflow.
        let overflow = self.buckets();
        let (mut min, mut sum, mut count) = (f64::INFINITY, 0.0, 0usize);
        let mut j = self.heads[overflow];
        while j != NONE {
            let t = self.records[j as usize].time;
            if t.is_finite() {
                min = min.min(t);
                sum += t;
                count += 1;
            }
            j = self.records[j as usize].next;
        }
        if count == 0 {
            self.current = self.cycle_end.saturating_sub(1);
            return false;
        }
        // Pending times spread over about twice their mean delay after the earliest.
        let mean_delay = sum / count as f64 - min;
        let width = 2.0 * mean_delay * EVENTS_PER_BUCKET / count as f64;
        self.width = if width > 0.0 && width.is_finite() {
            // The width keeps t / width well inside u64.
            width.max(min.abs() * 1e-15).max(f64::MIN_POSITIVE)
        } else {
            min.abs().max(1.0) * 1e-9
        };
        self.current = self.bucket_of(min);
        self.cycle_end = self.current.saturating_add(self.buckets() as u64);
        let mut j = std::mem::replace(&mut self.heads[overflow], NONE);
        while j != NONE {
            let next = self.records[j as usize].next;
            self.file(j as usize);
            j = next;
        }
        true
    }

    fn heap_push(&mut self, i: usize) {
        let r = &mut self.records[i];
        r.place = IN_HEAP;
        let t = r.time;
        self.heap.push((t, i as u32));
        self.sift_up(self.heap.len() - 1);
    }

    fn heap_remove(&mut self, s: usize) {
        let last = self.heap.len() - 1;
        self.heap.swap(s, last);
        self.heap.pop();
        if s < self.heap.len() {
            self.records[self.heap[s].1 as usize].heap_slot = s as u32;
            self.sift_down(s);
            self.sift_up(s);
        }
    }

    fn sift_up(&mut self, mut s: usize) {
        while s > 0 {
            let parent = (s - 1) / 2;
            if self.heap[s].0 >= self.heap[parent].0 {
                break;
            }
            self.heap_swap(s, parent);
            s = parent;
        }
        self.records[self.heap[s].1 as usize].heap_slot = s as u32;
    }

    fn sift_down(&mut self, mut s: usize) {
        let n = self.heap.len();
        loop {
            let (l, r) = (2 * s + 1, 2 * s + 2);
            let mut smallest = s;
            if l < n && self.heap[l].0 < self.heap[smallest].0 {
                smallest = l;
            }
            if r < n && self.heap[r].0 < self.heap[smallest].0 {
                smallest = r;
            }
            if smallest == s {
                break;
            }
            self.heap_swap(s, smallest);
            s = smallest;
        }
        self.records[self.heap[s].1 as usize].heap_slot = s as u32;
    }

    fn heap_swap(&mut self, a: usize, b: usize) {
        self.heap.swap(a, b);
        self.records[self.heap[a].1 as usize].heap_slot = a as u32;
        self.records[self.heap[b].1 as usize].heap_slot = b as u32;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Random updates, mostly a little after the current minimum (as in eMD), some far
    /// ahead, some infinite: peek always gives the true minimum.
    #[test]
    fn orders_updates_like_a_heap() {
        for n in [1, 2, 5, 100, 1000] {
            let mut q = BucketSorter::new(n);
            let mut times = vec![f64::INFINITY; n];
            let mut x = 987654321u64;
            let mut uniform = || {
                x = x
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                (x >> 11) as f64 / (1u64 << 53) as f64
            };
            let mut now = 0.0;
            for step in 0..20_000 {
                let (i, t) = q.peek().unwrap();
                let min = times.iter().cloned().fold(f64::INFINITY, f64::min);
                assert_eq!(t, min, "n {n} step {step}");
                if t.is_finite() {
                    assert_eq!(times[i], t);
                    now = t;
                }
                let k = (uniform() * n as f64) as usize % n;
                let u = uniform();
                let new = if u < 0.01 {
                    f64::INFINITY
                } else if u < 0.05 {
                    now + 1e3 * uniform()
                } else {
                    now + uniform()
                };
                let who = if uniform() < 0.5 && t.is_finite() {
                    i
                } else {
                    k
                };
                q.update(who, new);
                times[who] = new;
            }
        }
    }
}
