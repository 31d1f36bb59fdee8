//! Errors that point at the place in a scene file where the problem is.

/// A problem in a scene file, shown as `FILE:LINE:COL: what is wrong and what was expected`.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{file}:{line}:{column}: {message}")]
pub struct SceneError {
    /// The file's path as the user gave it (or a label such as `<string>`).
    pub file: String,
    /// 1-based line.
    pub line: usize,
    /// 1-based column, counted in characters.
    pub column: usize,
    /// What is wrong and what was expected.
    pub message: String,
}

/// A problem with a scene as a whole (no file position), e.g. a scene built in
/// code that names a material nobody defined.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct InvalidScene(pub String);
