//! Placeholder, replaced below.
#[derive(Debug, Clone, PartialEq)]
pub struct ParseErrors(pub Vec<String>);
impl std::fmt::Display for ParseErrors {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", self.0.join("\n"))
    }
}
impl std::error::Error for ParseErrors {}
