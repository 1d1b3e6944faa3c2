//! What a placeholder is worth to a robot looking for something: the goals of goal-driven
//! exploration (issue 35; CogX report, annex 2.5: the planner chooses which placeholder to
//! explore by the probabilities the conceptual map gives it).
//!
//! A goal turns each placeholder into a [`Target`] whose value is the probability that going
//! through it reaches what the goal asks for: a room not yet in the map (`P(NewRoom)`), or a
//! new room of a given type (`P(NewRoom) · P(type)`, the type read as independent of whether
//! the space is new, as the rules give it). The robot ([`crate::explore::Explorer`]) then drives
//! to the target with the most value per metre.

use crate::explore::Target;
use crate::floorplan::world::{Placeholder, UnitType};

/// A goal's name that [`Goal::parse`] does not know; it says which names it knows.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UnknownGoal {
    name: String,
}

impl UnknownGoal {
    /// The name given.
    pub fn name(&self) -> &str {
        &self.name
    }
}

impl std::fmt::Display for UnknownGoal {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "unknown goal {:?}: give new-room, room, corridor, hall or other", self.name)
    }
}

impl std::error::Error for UnknownGoal {}

/// What the robot is looking for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Goal {
    /// Any room not yet in the map.
    NewRoom,
    /// A new space of this type (room, corridor, hall or other).
    Find(UnitType),
}

impl Goal {
    /// The goal a name gives: `new-room`, or a type's name (`room`, `corridor`, `hall`,
    /// `other`).
    ///
    /// ```
    /// use ksmcmc::floorplan::frontier::Goal;
    /// use ksmcmc::floorplan::world::UnitType;
    ///
    /// assert_eq!(Goal::parse("hall"), Ok(Goal::Find(UnitType::Hall)));
    /// let e = Goal::parse("kitchen").unwrap_err();
    /// assert_eq!(e.name(), "kitchen");
    /// assert_eq!(e.to_string(), r#"unknown goal "kitchen": give new-room, room, corridor, hall or other"#);
    /// ```
    pub fn parse(name: &str) -> Result<Goal, UnknownGoal> {
        match name {
            "new-room" => Ok(Goal::NewRoom),
            "room" => Ok(Goal::Find(UnitType::Room)),
            "corridor" => Ok(Goal::Find(UnitType::Corridor)),
            "hall" => Ok(Goal::Find(UnitType::Hall)),
            "other" => Ok(Goal::Find(UnitType::Other)),
            _ => Err(UnknownGoal { name: name.to_owned() }),
        }
    }

    /// The goal's name, as [`Goal::parse`] reads it.
    pub fn name(self) -> &'static str {
        match self {
            Goal::NewRoom => "new-room",
            Goal::Find(t) => t.name(),
        }
    }

    /// Whether a space of type `kind` is what the goal asks for (any space, for a new room).
    pub fn wants(self, kind: UnitType) -> bool {
        match self {
            Goal::NewRoom => true,
            Goal::Find(t) => t == kind,
        }
    }

    /// The probability that going through `p` reaches what the goal asks for.
    pub fn value(self, p: &Placeholder) -> f64 {
        let t = &p.types;
        p.p_new_room
            * match self {
                Goal::NewRoom => 1.0,
                Goal::Find(UnitType::Room) => t.room,
                Goal::Find(UnitType::Corridor) => t.corridor,
                Goal::Find(UnitType::Hall) => t.hall,
                Goal::Find(UnitType::Other) => t.other,
                Goal::Find(UnitType::Unknown) => 0.0,
            }
    }

    /// The placeholders as targets for this goal, in their order.
    ///
    /// ```
    /// use ksmcmc::floorplan::frontier::Goal;
    /// use ksmcmc::floorplan::world::{Placeholder, TypeProbabilities, UnitType};
    /// let types = TypeProbabilities { room: 0.5, corridor: 0.1, hall: 0.3, other: 0.1 };
    /// let p = Placeholder { id: 1, x: 4, y: 7, width_m: 1.0, room: 2, p_new_room: 0.8, types };
    /// let t = Goal::Find(UnitType::Hall).targets(&[p]);
    /// assert_eq!(t[0].cell, (4, 7));
    /// assert!((t[0].value - 0.24).abs() < 1e-12);
    /// ```
    pub fn targets(self, placeholders: &[Placeholder]) -> Vec<Target> {
        placeholders
            .iter()
            .filter(|p| p.x >= 0 && p.y >= 0)
            .map(|p| Target { cell: (p.x as usize, p.y as usize), value: self.value(p) })
            .collect()
    }
}
