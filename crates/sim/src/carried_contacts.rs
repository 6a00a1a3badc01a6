//! The contacts a step's check detects at the state the step ended in, carried over to the
//! next step, which takes them over instead of detecting again: detection runs once per step.

use glam::DVec3;
use hagfish_geometry::{Centreline, DetectionReport, SelfContact, WallContact};

use crate::step_data::StepData;

/// The contact geometry of the state the last step (or [`crate::World::set_state`]) ended in:
/// body centres, centreline, self and wall contacts and the detection's counts, kept apart
/// from the step data's own (those of the step's start, which its report describes).
#[derive(Debug)]
pub(crate) struct CarriedContacts {
    pub(crate) centres: Vec<DVec3>,
    pub(crate) centreline: Centreline,
    pub(crate) self_contacts: Vec<SelfContact>,
    pub(crate) wall_contacts: Vec<WallContact>,
    /// The counts of their detection.
    pub(crate) detection: DetectionReport,
    /// Whether they are the current state's.
    pub(crate) status: Carried,
}

/// Whether the carried contacts describe the world's current state.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Carried {
    /// They are the current state's (and the tree kinematics of the step data too): the next
    /// step takes them over.
    Current,
    /// Out of date or never detected: the next step detects its own.
    Stale,
}

impl StepData {
    /// Makes the carried contacts this step's own, if they are the current state's
    /// (O(1): buffers are exchanged, not copied); they are stale afterwards. Returns their
    /// status before.
    pub(crate) fn take_over_carried(&mut self) -> Carried {
        let status = self.carried.status;
        if status == Carried::Current {
            self.exchange_carried();
            self.report.detection = self.carried.detection;
            self.carried.status = Carried::Stale;
        }
        status
    }

    /// Runs `detect` with the carried contacts in place of the step's own (so that it fills
    /// them), then puts the step's own back.
    pub(crate) fn with_carried<R>(&mut self, detect: impl FnOnce(&mut StepData) -> R) -> R {
        self.exchange_carried();
        let result = detect(self);
        self.exchange_carried();
        result
    }

    /// Exchanges the contact geometry with the carried one: O(1), no copies.
    fn exchange_carried(&mut self) {
        std::mem::swap(&mut self.centres, &mut self.carried.centres);
        std::mem::swap(&mut self.centreline, &mut self.carried.centreline);
        std::mem::swap(&mut self.self_contacts, &mut self.carried.self_contacts);
        std::mem::swap(&mut self.wall_contacts, &mut self.carried.wall_contacts);
    }
}
