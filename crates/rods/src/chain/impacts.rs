//! Counting impacts from contact episodes.

use super::CollisionRecord;
use serde::{Deserialize, Serialize};

/// Counts impacts from contact episodes: with finitely many modes the rod ends ring, so
/// one impact opens and closes its contact several times. An episode of contact k (rods k
/// and k+1) starts a new impact unless both rods' previous episode was at contact k too
/// (in 1D a pair can only meet again after one of them hit its other neighbour).
///
/// It serializes completely (check-points of a running chain).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Impacts {
    /// Per rod: the contact of its last episode (`usize::MAX`: none yet).
    last_contact: Vec<usize>,
    /// Impacts counted so far.
    collisions: u64,
}

impl Impacts {
    /// No impacts yet on a ring of `rods` rods.
    pub fn new(rods: usize) -> Self {
        Impacts {
            last_contact: vec![usize::MAX; rods],
            collisions: 0,
        }
    }

    /// Counts the impacts among `episodes` (completed contact episodes, e.g. from
    /// [`super::Chain::run_until`], in any order: they are taken by start time).
    pub fn count(&mut self, episodes: &[CollisionRecord]) {
        let n = self.last_contact.len();
        let mut sorted: Vec<_> = episodes.iter().map(|e| (e.t_start, e.contact)).collect();
        sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (_, k) in sorted {
            let (left, right) = (k, (k + 1) % n);
            if self.last_contact[left] != k || self.last_contact[right] != k {
                self.collisions += 1;
            }
            self.last_contact[left] = k;
            self.last_contact[right] = k;
        }
    }

    /// The number of rods on the ring.
    pub fn rods(&self) -> usize {
        self.last_contact.len()
    }

    /// Impacts counted so far.
    pub fn collisions(&self) -> u64 {
        self.collisions
    }

    /// Collisions per particle: 2 × impacts / N (each impact involves two rods).
    pub fn per_particle(&self) -> f64 {
        2.0 * self.collisions as f64 / self.last_contact.len() as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn episode(contact: usize, t_start: f64) -> CollisionRecord {
        CollisionRecord {
            contact,
            t_start,
            t_end: t_start + 0.1,
            v_pre: -1.0,
            v_post: 1.0,
            rel_v2_integral: 0.0,
        }
    }

    #[test]
    fn ringing_episodes_are_one_impact() {
        // 4 rods: contact 1 rings three times (one impact), then contact 2 (rods 2, 3),
        // then contact 1 again: rod 2 hit rod 3 meanwhile, so it is a new impact.
        let mut impacts = Impacts::new(4);
        impacts.count(&[episode(1, 0.0), episode(1, 0.2), episode(1, 0.4)]);
        assert_eq!(impacts.collisions(), 1);
        impacts.count(&[episode(2, 1.0)]);
        assert_eq!(impacts.collisions(), 2);
        impacts.count(&[episode(1, 2.0), episode(1, 2.3)]);
        assert_eq!(impacts.collisions(), 3);
        assert_eq!(impacts.per_particle(), 1.5);
    }

    #[test]
    fn episodes_are_taken_by_start_time_and_wrap_around_the_ring() {
        // contact 2 of 3 rods joins rods 2 and 0; given out of order
        let mut a = Impacts::new(3);
        a.count(&[episode(2, 0.5), episode(0, 0.7), episode(2, 0.1)]);
        // 0.1: contact 2 (new), 0.5: contact 2 again (same impact), 0.7: contact 0 (new)
        assert_eq!(a.collisions(), 2);
        let mut b = Impacts::new(3);
        b.count(&[episode(2, 0.1), episode(0, 0.3), episode(2, 0.5)]);
        // rod 0 hit rod 1 between the two episodes of contact 2: three impacts
        assert_eq!(b.collisions(), 3);
    }

    #[test]
    fn serde_keeps_the_state() {
        let mut a = Impacts::new(3);
        a.count(&[episode(1, 0.0)]);
        let text = serde_json::to_string(&a).unwrap();
        assert_eq!(
            text,
            r#"{"last_contact":[18446744073709551615,1,1],"collisions":1}"#
        );
        assert_eq!(serde_json::from_str::<Impacts>(&text).unwrap(), a);
    }
}
