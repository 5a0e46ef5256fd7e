//! Errors of loading and validating models. Every error names the file it comes from and,
//! where there is one, the field (a dotted path such as `objects[2].mu_c`).

use crate::validity::Invalid;
use std::fmt;
use std::path::{Path, PathBuf};

/// A model-loading error. Display gives `file: field: message`.
#[derive(Debug, Clone, PartialEq)]
pub enum Error {
    /// The file could not be read.
    Io {
        /// The file.
        file: PathBuf,
        /// Why it could not be read.
        message: String,
    },
    /// The file is not well-formed (syntax, unknown key, wrong type).
    Parse {
        /// The file.
        file: PathBuf,
        /// The field, a dotted path (`objects[2].mu_c`); empty for the whole file.
        field: String,
        /// What is wrong.
        message: String,
    },
    /// A value is well-formed but not acceptable (negative mass, NaN, goal off the table
    /// ...).
    Invalid {
        /// The file.
        file: PathBuf,
        /// The field, a dotted path (`objects[2].mu_c`).
        field: String,
        /// What is wrong with its value.
        message: String,
    },
    /// The robot description (URDF) is unusable.
    Urdf {
        /// The URDF file.
        file: PathBuf,
        /// What is wrong with it.
        message: String,
    },
    /// The URDF has no link of the end effector's name: the fault of whoever named it
    /// (a scene's `robot.end_effector`).
    NoEndEffector {
        /// The URDF file.
        file: PathBuf,
        /// Which link is missing, and the links there are.
        message: String,
    },
    /// A collision mesh is missing or unusable.
    Mesh {
        /// The mesh file.
        file: PathBuf,
        /// What is wrong with it.
        message: String,
    },
    /// The scene's start state violates a validity rule.
    InvalidStart {
        /// The scene file.
        file: PathBuf,
        /// The rule broken.
        rule: Invalid,
    },
    /// An observed start the model has no state near ([`crate::Scene::with_start`]): a
    /// link reaches into an object, or two objects into each other, further than an
    /// observation may be off ([`crate::scene::MAX_SEPARATION`]).
    DeepOverlap {
        /// The file the state came from.
        file: PathBuf,
        /// The object moved out of the overlap, a dotted path (`objects.glass_5`).
        field: String,
        /// What overlaps.
        between: Overlap,
        /// How deep, and what was tried.
        message: String,
    },
}

/// What overlaps in an [`Error::DeepOverlap`]: what a robot can undo by moving its arm
/// back, or not.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Overlap {
    /// A link of the arm and an object.
    ArmAndObject,
    /// Two objects.
    Objects,
}

impl Error {
    /// The file could not be read: `message` says why.
    pub fn io(file: &Path, message: impl Into<String>) -> Self {
        Error::Io {
            file: file.to_path_buf(),
            message: message.into(),
        }
    }

    /// A value of `field` in `file` is not acceptable: `message` says why.
    pub fn invalid(file: &Path, field: impl Into<String>, message: impl Into<String>) -> Self {
        Error::Invalid {
            file: file.to_path_buf(),
            field: field.into(),
            message: message.into(),
        }
    }

    /// The file the error is about.
    pub fn file(&self) -> &Path {
        match self {
            Error::Io { file, .. }
            | Error::Parse { file, .. }
            | Error::Invalid { file, .. }
            | Error::Urdf { file, .. }
            | Error::NoEndEffector { file, .. }
            | Error::Mesh { file, .. }
            | Error::InvalidStart { file, .. }
            | Error::DeepOverlap { file, .. } => file,
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Io { file, message } => {
                write!(f, "{}: cannot read: {message}", file.display())
            }
            Error::Parse {
                file,
                field,
                message,
            } => {
                if field.is_empty() || field == "." {
                    write!(f, "{}: {message}", file.display())
                } else {
                    write!(f, "{}: {field}: {message}", file.display())
                }
            }
            Error::Invalid {
                file,
                field,
                message,
            }
            | Error::DeepOverlap {
                file,
                field,
                message,
                ..
            } => write!(f, "{}: {field}: {message}", file.display()),
            Error::Urdf { file, message } | Error::NoEndEffector { file, message } => {
                write!(f, "{}: URDF: {message}", file.display())
            }
            Error::Mesh { file, message } => {
                write!(f, "{}: mesh: {message}", file.display())
            }
            Error::InvalidStart { file, rule } => {
                write!(f, "{}: start state is invalid: {rule}", file.display())
            }
        }
    }
}

impl std::error::Error for Error {}

/// A result whose error is a model-loading [`Error`].
pub type Result<T> = std::result::Result<T, Error>;
