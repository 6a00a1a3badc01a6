//! Which recorded frames the report holds: every frame, or — for a run whose frames × bodies
//! exceed [`BODY_FRAME_BUDGET`] — every s-th frame and the last, so that what the report
//! holds does not grow with the length of a run of many bodies. `metrics.csv` (a line per
//! frame) and the tension at the head are always read whole.

/// Body centres (frames × bodies) the report holds at most, with the thigmotaxic forces and
/// tensions of the same frames ≈ 56 bytes each: ≈ 110 MB. That is 20 000 frames of 100
/// bodies (a run of 2000 s recorded every 0.1 s) and 200 frames of 10 000 bodies.
pub const BODY_FRAME_BUDGET: usize = 2_000_000;

/// The frames kept: those whose index is a multiple of `stride`, and `last`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FrameSelection {
    /// Every `stride`-th frame is kept (1: all).
    pub stride: usize,
    /// A frame kept whatever the stride: the run's last.
    pub last: Option<usize>,
}

impl FrameSelection {
    /// Every frame.
    pub fn all() -> Self {
        Self { stride: 1, last: None }
    }

    /// The least stride that keeps at most about `budget` body centres of a run of `frames`
    /// frames of `bodies` bodies, and the last frame (one more than the budget, at most).
    pub fn within(frames: usize, bodies: usize, budget: usize) -> Self {
        let stride = frames.saturating_mul(bodies).div_ceil(budget.max(1)).max(1);
        Self { stride, last: frames.checked_sub(1) }
    }

    /// Whether frame `f` is kept.
    pub fn keeps(&self, f: usize) -> bool {
        f.is_multiple_of(self.stride) || Some(f) == self.last
    }

    /// The frames kept of the first `frames`, in order.
    pub fn kept(&self, frames: usize) -> impl Iterator<Item = usize> + '_ {
        (0..frames).filter(|&f| self.keeps(f))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_run_within_the_budget_keeps_every_frame() {
        let selection = FrameSelection::within(901, 100, BODY_FRAME_BUDGET);
        assert_eq!(selection.stride, 1);
        assert_eq!(selection.kept(901).count(), 901);
        assert!((0..10).all(|f| FrameSelection::all().keeps(f)));
    }

    #[test]
    fn a_longer_run_keeps_every_s_th_frame_and_the_last() {
        // 601 frames of 10 000 bodies: 6 010 000 centres, a stride of 4.
        let selection = FrameSelection::within(601, 10_000, BODY_FRAME_BUDGET);
        assert_eq!(selection.stride, 4);
        let kept: Vec<usize> = selection.kept(601).collect();
        assert_eq!((kept[..3].to_vec(), kept.len()), (vec![0, 4, 8], 151));
        assert_eq!(kept.last(), Some(&600));
        let odd = FrameSelection::within(10, 1, 3);
        assert_eq!(odd.kept(10).collect::<Vec<_>>(), [0, 4, 8, 9], "stride 4 and the last");
    }
}
