//! The kinds of DOF of the body's joints and the selections of them: the DOFs a modal
//! decomposition of the force field takes (`hagfish modes --kind`), and those whose mode shapes
//! span a modal force space ([`crate::ForceSpace::Modes`]).

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

/// The kind of one DOF, from its axis in the joint frame (`forces.csv`'s `axis`): X is the
/// twist about the body axis, Y and Z the two bends.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DofKind {
    /// Rotation about the body axis (X).
    Twist,
    /// Bending about the joint's Y axis.
    BendY,
    /// Bending about the joint's Z axis.
    BendZ,
}

impl DofKind {
    /// The kind of a DOF about axis `axis` (`'X'`, `'Y'` or `'Z'`); `None` for another.
    pub fn from_axis(axis: char) -> Option<Self> {
        match axis {
            'X' => Some(Self::Twist),
            'Y' => Some(Self::BendY),
            'Z' => Some(Self::BendZ),
            _ => None,
        }
    }

    /// The DOF's axis in the joint frame, the inverse of [`DofKind::from_axis`].
    pub fn axis(self) -> char {
        match self {
            Self::Twist => 'X',
            Self::BendY => 'Y',
            Self::BendZ => 'Z',
        }
    }
}

/// Which DOFs a decomposition takes: all together, both bends, or one kind. The field of
/// several kinds is decomposed as one matrix (the kinds share the unit dyn·cm). Written in a
/// scenario by its [`name`](KindSelection::name), e.g. `kind: "bend"`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(try_from = "String", into = "String")]
pub enum KindSelection {
    /// Every DOF.
    All,
    /// Both bending DOFs (Y and Z), no twist: what the bending muscles produce.
    Bend,
    /// The Y bends.
    BendY,
    /// The Z bends.
    BendZ,
    /// The twists.
    Twist,
}

impl KindSelection {
    /// Every selection, in the order `hagfish modes` reports them.
    pub const EVERY: [Self; 5] = [Self::All, Self::Bend, Self::BendY, Self::BendZ, Self::Twist];

    /// Whether a DOF of `kind` is selected.
    pub fn includes(self, kind: DofKind) -> bool {
        match self {
            Self::All => true,
            Self::Bend => kind != DofKind::Twist,
            Self::BendY => kind == DofKind::BendY,
            Self::BendZ => kind == DofKind::BendZ,
            Self::Twist => kind == DofKind::Twist,
        }
    }

    /// The name used on the command line and in the output files.
    pub fn name(self) -> &'static str {
        match self {
            Self::All => "all",
            Self::Bend => "bend",
            Self::BendY => "bend-y",
            Self::BendZ => "bend-z",
            Self::Twist => "twist",
        }
    }
}

impl fmt::Display for KindSelection {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for KindSelection {
    type Err = String;

    /// Parses a [`KindSelection::name`].
    fn from_str(text: &str) -> Result<Self, Self::Err> {
        Self::EVERY.into_iter().find(|k| k.name() == text).ok_or_else(|| {
            let names: Vec<_> = Self::EVERY.iter().map(|k| k.name()).collect();
            format!("unknown DOF kind {text:?}: expected one of {}", names.join(", "))
        })
    }
}

impl TryFrom<String> for KindSelection {
    type Error = String;

    /// Parses a [`KindSelection::name`] (the scenario format's spelling).
    fn try_from(text: String) -> Result<Self, Self::Error> {
        text.parse()
    }
}

impl From<KindSelection> for String {
    /// The selection's [`KindSelection::name`].
    fn from(kind: KindSelection) -> Self {
        kind.name().to_owned()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_parse_back_and_bend_excludes_twist() {
        for k in KindSelection::EVERY {
            assert_eq!(k.name().parse::<KindSelection>(), Ok(k));
        }
        assert!("bendy".parse::<KindSelection>().is_err());
        assert!(!KindSelection::Bend.includes(DofKind::Twist));
        assert!(KindSelection::Bend.includes(DofKind::BendZ));
        assert_eq!(DofKind::from_axis('W'), None);
        assert_eq!(DofKind::from_axis(DofKind::BendZ.axis()), Some(DofKind::BendZ));
    }
}
