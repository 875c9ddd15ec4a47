//! Where generated code finds the crates it names: `rover_dynamics` (the
//! plant traits, nalgebra, the wheel-ground code) and `libm` (the math
//! functions).
//!
//! The standalone module of `rover codegen` names them directly, for a
//! `no_std` crate that depends on both. The derive's code is compiled in
//! the user's crate, whose dependencies are those the README names
//! (`rover-derive`, `rover-runtime`, `rover-scenario`): by default it
//! names them through `::rover_runtime::__private`, which re-exports both;
//! `#[rover(no_std = true, …)]` names them directly, for firmware that
//! depends on `rover-dynamics` and `libm` instead of the runtime.

use proc_macro2::{Ident, Literal, Punct, Spacing, Span, TokenStream, TokenTree};

/// The crates generated code names.
const NAMED: [&str; 2] = ["rover_dynamics", "libm"];

/// How generated code reaches `rover_dynamics` and `libm`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Crates {
    /// Through `::rover_runtime::__private`: a crate that depends on
    /// `rover-runtime` (the derive's default).
    #[default]
    Runtime,
    /// `::rover_dynamics` and `::libm`: a crate that depends on both (the
    /// standalone module; the derive's `no_std = true`).
    Direct,
}

/// `tokens` (written with `::rover_dynamics` and `::libm`) with the paths
/// of `crates`: each absolute path starting with one of the two crates,
/// and each such path quoted in documentation, rerouted.
pub fn route(tokens: TokenStream, crates: Crates) -> TokenStream {
    match crates {
        Crates::Direct => tokens,
        Crates::Runtime => reroute(tokens),
    }
}

fn reroute(tokens: TokenStream) -> TokenStream {
    let trees: Vec<TokenTree> = tokens.into_iter().collect();
    let mut out = Vec::with_capacity(trees.len());
    let mut i = 0;
    while i < trees.len() {
        if let Some(span) = absolute_path_start(&trees, i) {
            // `::rover_runtime::__private` before the crate's `::name`.
            out.extend(colons(span));
            out.push(TokenTree::Ident(Ident::new("rover_runtime", span)));
            out.extend(colons(span));
            out.push(TokenTree::Ident(Ident::new("__private", span)));
        }
        out.push(match &trees[i] {
            TokenTree::Group(g) => {
                let mut group = proc_macro2::Group::new(g.delimiter(), reroute(g.stream()));
                group.set_span(g.span());
                TokenTree::Group(group)
            }
            TokenTree::Literal(lit) => TokenTree::Literal(reroute_doc(lit)),
            t => t.clone(),
        });
        i += 1;
    }
    out.into_iter().collect()
}

/// The span of `::` at `i` if it starts an absolute path to one of the
/// named crates (not preceded by a path segment).
fn absolute_path_start(trees: &[TokenTree], i: usize) -> Option<Span> {
    let (TokenTree::Punct(a), Some(TokenTree::Punct(b)), Some(TokenTree::Ident(name))) =
        (&trees[i], trees.get(i + 1), trees.get(i + 2))
    else {
        return None;
    };
    let joined = a.as_char() == ':' && a.spacing() == Spacing::Joint && b.as_char() == ':';
    // `a::rover_dynamics` is relative; `impl ::…`, `as ::…` are not (a
    // keyword does not parse as an identifier).
    let after_segment = match i.checked_sub(1).map(|k| &trees[k]) {
        Some(TokenTree::Ident(prev)) => syn::parse_str::<Ident>(&prev.to_string()).is_ok(),
        _ => false,
    };
    (joined && !after_segment && NAMED.iter().any(|n| name == n)).then(|| a.span())
}

fn colons(span: Span) -> [TokenTree; 2] {
    let mut first = Punct::new(':', Spacing::Joint);
    first.set_span(span);
    let mut second = Punct::new(':', Spacing::Alone);
    second.set_span(span);
    [TokenTree::Punct(first), TokenTree::Punct(second)]
}

/// A string literal (documentation) quoting `::rover_dynamics::…`, with
/// the rerouted path, so that its links resolve in the user's crate.
fn reroute_doc(lit: &Literal) -> Literal {
    let text = lit.to_string();
    if !text.starts_with('"') || !NAMED.iter().any(|n| text.contains(&format!("::{n}::"))) {
        return lit.clone();
    }
    let mut routed = text;
    for name in NAMED {
        routed = routed.replace(
            &format!("`::{name}::"),
            &format!("`::rover_runtime::__private::{name}::"),
        );
    }
    match routed.parse::<Literal>() {
        Ok(mut new) => {
            new.set_span(lit.span());
            new
        }
        Err(_) => lit.clone(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use quote::quote;

    #[test]
    fn absolute_paths_go_through_the_runtime() {
        let code = quote! {
            impl ::rover_dynamics::plant::Plant for P {
                #[doc = "see [`::rover_dynamics::cpu`]"]
                fn f(x: f64) -> f64 { ::libm::sin(x) + <T as ::rover_dynamics::Plant>::DOF as f64 }
            }
            fn g(t: &[::rover_dynamics::Tyre]) -> ::libm::X { other::rover_dynamics::x(); ::rover_dynamics_extra::y(); }
        };
        let routed = route(code.clone(), Crates::Runtime).to_string();
        assert!(
            routed.contains(
                "impl :: rover_runtime :: __private :: rover_dynamics :: plant :: Plant for P"
            ),
            "{routed}"
        );
        assert!(routed.contains(":: rover_runtime :: __private :: libm :: sin (x)"));
        assert!(
            routed.contains("< T as :: rover_runtime :: __private :: rover_dynamics :: Plant >")
        );
        assert!(routed.contains("[`::rover_runtime::__private::rover_dynamics::cpu`]"));
        assert!(routed.contains("t : & [:: rover_runtime :: __private :: rover_dynamics :: Tyre]"));
        assert!(routed.contains("-> :: rover_runtime :: __private :: libm :: X"));
        // Relative paths and other crates are left alone.
        assert!(
            routed.contains("other :: rover_dynamics :: x ()"),
            "{routed}"
        );
        assert!(routed.contains("{ other"), "{routed}");
        assert!(
            routed.contains("; :: rover_dynamics_extra :: y ()"),
            "{routed}"
        );
        assert_eq!(
            route(code.clone(), Crates::Direct).to_string(),
            code.to_string()
        );
    }
}
