//! Closed sets of options named on the command line and in menus.

/// An enum whose variants have stable lower-case names.
pub trait Named: Copy + 'static {
    /// Every variant, in menu order.
    const VARIANTS: &'static [Self];
    /// The variant's name on the command line and in menus.
    fn label(self) -> &'static str;
}

/// The variant called `s`, or an error listing the names.
///
/// # Errors
/// `s` names no variant; the message lists the valid names.
pub fn parse_named<T: Named>(s: &str, what: &str) -> Result<T, String> {
    T::VARIANTS
        .iter()
        .copied()
        .find(|v| v.label() == s)
        .ok_or_else(|| {
            let names: Vec<_> = T::VARIANTS.iter().map(|v| v.label()).collect();
            format!(
                "unknown {what} '{s}', expected one of: {}",
                names.join(", ")
            )
        })
}

/// Implements [`Named`], `FromStr` and `Display` from an enum's `ALL` and `name()`.
#[macro_export]
macro_rules! named_enum {
    ($t:ty, $what:literal) => {
        impl $crate::names::Named for $t {
            const VARIANTS: &'static [Self] = &<$t>::ALL;
            fn label(self) -> &'static str {
                self.name()
            }
        }
        impl std::str::FromStr for $t {
            type Err = String;
            fn from_str(s: &str) -> Result<Self, String> {
                $crate::names::parse_named(s, $what)
            }
        }
        impl std::fmt::Display for $t {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.name())
            }
        }
    };
}
