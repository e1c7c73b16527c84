//! Identities the stages share: which body ([`BodyId`]) and which gaze
//! target ([`TargetId`]: a body or a point, where on it, and who chose it).
//! Typed, so a body is never confused with a count or a segment, and a
//! target is compared by what it is, not by its name.

/// A typed handle to one body of the world vision looks at: the bodies are
/// numbered `0..n` ([`crate::vision::Scenery::body_count`]) and never renumbered while a
/// world lives, so a handle names the same body from tick to tick. Use it
/// to index per-body tables with [`BodyId::index`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct BodyId(usize);

impl BodyId {
    /// The body numbered `i`.
    pub const fn new(i: usize) -> Self {
        BodyId(i)
    }

    /// Its number, for indexing per-body tables.
    pub const fn index(self) -> usize {
        self.0
    }

    /// Every body of a world of `n` bodies, in order.
    pub fn all(n: usize) -> impl Iterator<Item = BodyId> {
        (0..n).map(BodyId)
    }
}

impl std::fmt::Display for BodyId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "body {}", self.0)
    }
}

/// Where a gaze choice came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Source {
    /// Motion saliency won (M1).
    BottomUp,
    /// The action's request won.
    TopDown,
    /// A scene's gaze override.
    Override,
}

impl Source {
    /// Name used in traces.
    pub fn as_str(self) -> &'static str {
        match self {
            Source::BottomUp => "bottom_up",
            Source::TopDown => "top_down",
            Source::Override => "override",
        }
    }
}

/// Where on its body a gaze target lies.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Spot {
    /// The body itself (its centre, or a point near it); named after the
    /// body. A target with no body is a fixed point.
    #[default]
    Centre,
    /// The opponent's trunk, below its head ("opponent_body"): the
    /// fighters' bodies carry no body of their own for it.
    Trunk,
}

/// A gaze target's identity from tick to tick: the same identity while a
/// target moves, a new one when attention turns to something else. The
/// oculomotor starts a new reaction time (H1) when it changes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct TargetId {
    /// Who chose it.
    pub source: Source,
    /// The body it rides on; `None` for a fixed point.
    pub body: Option<BodyId>,
    /// Where on that body.
    pub spot: Spot,
}

impl TargetId {
    /// Body `b` itself, asked for top-down: what a host application that
    /// aims the gaze itself passes (one body per thing it looks at).
    pub fn body(b: BodyId) -> Self {
        TargetId {
            source: Source::TopDown,
            body: Some(b),
            spot: Spot::Centre,
        }
    }
}
