//! The trial bookkeeping the 3D laws share ([`Held`]): a 3D solver whose step changes a
//! state it can snapshot and restore ([`Restorable`]) becomes a law whose trial starts
//! from the accepted state, whose rejected trial is taken back bit for bit, and whose
//! failed step leaves the accepted state as it was.

use crate::law::Forces;
use crate::{bad, Result};
use bem3d::adhesion::{AdhesiveContact, AdhesiveSnapshot};
use bem3d::tangential::{SlipSnapshot, ViscoelasticSlip};
use bem3d::viscoelastic::{Snapshot, TransientContact};
use bem3d::{HalfSpaceOperator, SlipOperator};

/// A solver whose step can be taken back: the state a step changes, and its return.
pub(crate) trait Restorable {
    type Snapshot;
    fn snapshot(&self) -> Self::Snapshot;
    /// Returns to a snapshot of this solver (another's is refused).
    fn restore(&mut self, s: Self::Snapshot) -> bem3d::Result<()>;
}

impl<O: HalfSpaceOperator> Restorable for AdhesiveContact<O> {
    type Snapshot = AdhesiveSnapshot;
    fn snapshot(&self) -> AdhesiveSnapshot {
        AdhesiveContact::snapshot(self)
    }
    fn restore(&mut self, s: AdhesiveSnapshot) -> bem3d::Result<()> {
        AdhesiveContact::restore(self, s)
    }
}

impl<O: HalfSpaceOperator> Restorable for TransientContact<O> {
    type Snapshot = Snapshot;
    fn snapshot(&self) -> Snapshot {
        TransientContact::snapshot(self)
    }
    fn restore(&mut self, s: Snapshot) -> bem3d::Result<()> {
        TransientContact::restore(self, s)
    }
}

impl<C: SlipOperator> Restorable for ViscoelasticSlip<C> {
    type Snapshot = SlipSnapshot;
    fn snapshot(&self) -> SlipSnapshot {
        ViscoelasticSlip::snapshot(self)
    }
    fn restore(&mut self, s: SlipSnapshot) -> bem3d::Result<()> {
        ViscoelasticSlip::restore(self, s)
    }
}

/// A restorable solver with its held trial and its accepted forces (module docs).
pub(crate) struct Held<C: Restorable> {
    pub(crate) solver: C,
    /// The state before the held trial.
    before: Option<C::Snapshot>,
    trial: Option<Forces>,
    committed: Forces,
}

impl<C: Restorable> Held<C> {
    /// `solver` in its accepted state, whose forces are `committed`.
    pub(crate) fn new(solver: C, committed: Forces) -> Self {
        Self {
            solver,
            before: None,
            trial: None,
            committed,
        }
    }

    /// Takes back a held trial: the solver is in the accepted state.
    pub(crate) fn settle(&mut self) -> Result<()> {
        self.trial = None;
        if let Some(s) = self.before.take() {
            self.solver.restore(s)?;
        }
        Ok(())
    }

    /// One trial: `step` from the accepted state, its forces held until
    /// [`Self::commit`] or [`Self::rollback`]; where `step` fails, the accepted state
    /// stays.
    pub(crate) fn trial(&mut self, step: impl FnOnce(&mut C) -> Result<Forces>) -> Result<Forces> {
        self.settle()?;
        let before = self.solver.snapshot();
        match step(&mut self.solver) {
            Ok(forces) => {
                self.before = Some(before);
                self.trial = Some(forces);
                Ok(forces)
            }
            Err(e) => {
                self.solver.restore(before)?;
                Err(e)
            }
        }
    }

    /// A query from the accepted state (`look` steps and reads), the state restored
    /// after it whatever it returns.
    pub(crate) fn query<T>(&mut self, look: impl FnOnce(&mut C) -> Result<T>) -> Result<T> {
        self.settle()?;
        let before = self.solver.snapshot();
        let out = look(&mut self.solver);
        self.solver.restore(before)?;
        out
    }

    pub(crate) fn commit(&mut self) -> Result<()> {
        let Some(forces) = self.trial.take() else {
            return bad("commit: no trial step to accept (call trial first)");
        };
        self.before = None;
        self.committed = forces;
        Ok(())
    }

    pub(crate) fn rollback(&mut self) {
        // A snapshot of this solver always fits it.
        let _ = self.settle();
    }

    pub(crate) fn committed(&self) -> Forces {
        self.committed
    }
}
