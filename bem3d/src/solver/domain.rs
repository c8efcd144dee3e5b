//! The cells that may touch: a caller's mask, or every cell without storing one (a
//! byte per cell saved on the unmasked grids, the large ones). The sweeps read it as
//! numbers (1 or 0 per cell, branch-free), by chunks of the same lengths as the other
//! buffers' chunks.

use rayon::iter::Either;
use rayon::prelude::*;

pub(super) struct Domain {
    /// 1 on cells that may touch, 0 elsewhere; None: every cell.
    cells: Option<Vec<u8>>,
    /// Ones for the chunks of an unmasked grid: as long as the longest chunk asked for.
    ones: Vec<u8>,
    len: usize,
}

impl Domain {
    /// Every one of `len` cells, read by chunks of at most `longest_chunk` cells.
    pub(super) fn all(len: usize, longest_chunk: usize) -> Self {
        Self {
            cells: None,
            ones: vec![1; longest_chunk.min(len)],
            len,
        }
    }

    /// The cells where `mask` is 1.
    pub(super) fn given(mask: Vec<u8>) -> Self {
        Self {
            len: mask.len(),
            cells: Some(mask),
            ones: Vec::new(),
        }
    }

    /// Whether cell `i` may touch.
    pub(super) fn holds(&self, i: usize) -> bool {
        self.cells.as_ref().is_none_or(|m| m[i] > 0)
    }

    /// The number of cells that may touch.
    pub(super) fn count(&self) -> usize {
        self.cells
            .as_ref()
            .map_or(self.len, |m| m.iter().filter(|&&m| m > 0).count())
    }

    /// A caller's mask (1 or 0 per cell), if one restricts the grid.
    pub(super) fn cells(&self) -> Option<&[u8]> {
        self.cells.as_deref()
    }

    /// The values (1 or 0) cell by cell.
    pub(super) fn iter(&self) -> impl Iterator<Item = &u8> + '_ {
        match &self.cells {
            Some(m) => Either::Left(m.iter()),
            None => Either::Right(std::iter::repeat_n(&1u8, self.len)),
        }
    }

    /// The values cell by cell, in parallel.
    pub(super) fn par_iter(&self) -> impl IndexedParallelIterator<Item = &u8> + '_ {
        match &self.cells {
            Some(m) => Either::Left(m.par_iter()),
            None => Either::Right(rayon::iter::repeat_n(&1u8, self.len)),
        }
    }

    /// The values by chunks of `ch` cells (the last one shorter), as `par_chunks`.
    pub(super) fn par_chunks(&self, ch: usize) -> impl IndexedParallelIterator<Item = &[u8]> + '_ {
        match &self.cells {
            Some(m) => Either::Left(m.par_chunks(ch)),
            None => {
                let (len, ones) = (self.len, &self.ones[..]);
                assert!(
                    ch <= ones.len() || len <= ones.len(),
                    "chunk longer than the ones"
                );
                Either::Right(
                    (0..len.div_ceil(ch))
                        .into_par_iter()
                        .map(move |b| &ones[..ch.min(len - b * ch)]),
                )
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_cell_reads_as_a_mask_of_ones() {
        // The same values, chunk lengths and counts as a stored mask of ones.
        for (len, ch) in [(0usize, 4usize), (1, 4), (12, 4), (13, 4), (13, 13), (5, 8)] {
            let all = Domain::all(len, ch);
            let ones = Domain::given(vec![1; len]);
            let a: Vec<&[u8]> = all.par_chunks(ch).collect();
            let b: Vec<&[u8]> = ones.par_chunks(ch).collect();
            assert_eq!(a, b, "{len} by {ch}");
            assert_eq!(all.iter().count(), len);
            assert_eq!(all.par_iter().count(), len);
            assert_eq!(all.count(), ones.count());
            assert!((0..len).all(|i| all.holds(i)));
            assert!(all.cells().is_none() && ones.cells() == Some(&vec![1; len][..]));
        }
        let some = Domain::given(vec![1, 0, 1, 1, 0, 0]);
        assert_eq!(some.count(), 3);
        assert!(some.holds(2) && !some.holds(4));
    }
}
