//! [`Memo`]: a value derived from the rest of its owner and computed on
//! first use, which takes no part in the owner's equality.

/// A value derived from the rest of its owner, computed on first use.
/// It is not part of what the owner is: any two compare equal.
#[derive(Clone)]
pub(crate) struct Memo<T>(pub(crate) std::sync::OnceLock<T>);

impl<T> Default for Memo<T> {
    fn default() -> Self {
        Memo(std::sync::OnceLock::new())
    }
}

impl<T> PartialEq for Memo<T> {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl<T> Eq for Memo<T> {}

impl<T> std::fmt::Debug for Memo<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(if self.0.get().is_some() {
            "Memo(computed)"
        } else {
            "Memo(not computed)"
        })
    }
}
