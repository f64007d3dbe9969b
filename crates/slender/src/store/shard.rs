//! `--shard i/n`: a deterministic split of a sweep's case list over n independent runs
//! (nodes of a cluster), merged afterwards with `slender merge`.

use std::fmt;
use std::str::FromStr;

/// Shard `index` of `count`: the cases whose position in the sweep's fixed order is
/// ≡ index (mod count). Round-robin keeps the expensive corner of a grid spread over shards.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// 0-based shard index (< count).
    pub index: usize,
    /// Number of shards (≥ 1).
    pub count: usize,
}

impl Shard {
    /// Whether the case at `position` of the sweep belongs to this shard.
    pub fn owns(self, position: usize) -> bool {
        position % self.count == self.index
    }
}

impl FromStr for Shard {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        let bad = || format!("--shard `{s}`: expected i/n with integers 0 <= i < n, e.g. 0/4");
        let (i, n) = s.split_once('/').ok_or_else(bad)?;
        let index: usize = i.trim().parse().map_err(|_| bad())?;
        let count: usize = n.trim().parse().map_err(|_| bad())?;
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Self { index, count })
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_and_rejects() {
        assert_eq!(
            "2/3".parse::<Shard>().unwrap(),
            Shard { index: 2, count: 3 }
        );
        for bad in ["3/3", "0/0", "1", "a/b", "-1/2", "1/2/3", ""] {
            let e = bad.parse::<Shard>().unwrap_err();
            assert!(e.contains("--shard"), "{bad}: {e}");
        }
    }

    #[test]
    fn shards_partition_the_cases() {
        for count in 1..6 {
            for pos in 0..50 {
                let owners = (0..count)
                    .filter(|&index| Shard { index, count }.owns(pos))
                    .count();
                assert_eq!(owners, 1);
            }
        }
    }
}
