//! The page's widgets for scripts, on request (`?widgets` in the page's address): the browser
//! test finds a button by its label, as a user does, and clicks it with the pointer.
//!
//! egui draws every widget itself on the canvas, so the page has no element per button. Asked,
//! the page turns on egui's AccessKit tree (the one a screen reader reads; off otherwise, it
//! costs a little every frame) and publishes each labelled widget after every frame as
//! `globalThis.texploreWidgets`: `{id, label, role, disabled, x, y, w, h}` in CSS pixels of the
//! page. `globalThis.texploreScrollTo(id)` scrolls a widget into view (AccessKit's
//! *ScrollIntoView*, which egui's scroll areas honour) for a widget below the fold, such as an
//! exercise's Check at the end of a lesson. The clicks themselves are the browser's own
//! (WebDriver's pointer), so nothing here presses anything.

use egui::accesskit;
use std::cell::RefCell;
use wasm_bindgen::JsValue;
use wasm_bindgen::closure::Closure;

thread_local! {
    /// Widgets a script asked to scroll into view, for the next frame's input.
    static SCROLL: RefCell<Vec<accesskit::NodeId>> = const { RefCell::new(Vec::new()) };
}

/// Whether the page's address asks for the widgets (`?widgets`).
#[must_use]
pub fn asked() -> bool {
    web_sys::window()
        .and_then(|w| w.location().search().ok())
        .is_some_and(|q| {
            q.trim_start_matches('?')
                .split('&')
                .any(|kv| kv == "widgets" || kv.starts_with("widgets="))
        })
}

/// Turns the widgets on for `ctx`: the tree, the plugin that publishes it, and
/// `texploreScrollTo`.
pub fn install(ctx: &egui::Context) {
    ctx.enable_accesskit();
    ctx.add_plugin(Publish::default());
    let scroll = Closure::<dyn FnMut(JsValue)>::new(|id: JsValue| {
        if let Some(id) = id.as_string().and_then(|s| s.parse::<u64>().ok()) {
            SCROLL.with(|s| s.borrow_mut().push(accesskit::NodeId(id)));
            super::repaint();
        }
    });
    let _ = js_sys::Reflect::set(
        &js_sys::global(),
        &"texploreScrollTo".into(),
        scroll.as_ref(),
    );
    scroll.forget();
}

/// Publishes the tree after each frame, and hands egui the scroll requests.
#[derive(Default)]
struct Publish {
    /// Frames still to draw after a scroll request: the scroll lands at the end of the frame
    /// that takes it, and the next one lays the widgets out where they went.
    after_scroll: u8,
}

impl egui::Plugin for Publish {
    fn debug_name(&self) -> &'static str {
        "texplore-widgets"
    }

    fn input_hook(&mut self, _ctx: &egui::Context, input: &mut egui::RawInput) {
        for target_node in SCROLL.with(|s| std::mem::take(&mut *s.borrow_mut())) {
            self.after_scroll = 2;
            input.events.push(egui::Event::AccessKitActionRequest(
                accesskit::ActionRequest {
                    action: accesskit::Action::ScrollIntoView,
                    target_tree: accesskit::TreeId::ROOT,
                    target_node,
                    data: None,
                },
            ));
        }
    }

    fn output_hook(&mut self, ctx: &egui::Context, output: &mut egui::FullOutput) {
        if self.after_scroll > 0 {
            self.after_scroll -= 1;
            ctx.request_repaint();
        }
        let Some(update) = &output.platform_output.accesskit_update else {
            return;
        };
        // egui's points to the page's CSS pixels (the canvas fills the page from its corner).
        let ratio = web_sys::window().map_or(1.0, |w| w.device_pixel_ratio());
        let scale = f64::from(ctx.pixels_per_point()) / ratio.max(1e-3);
        let list = js_sys::Array::new();
        for (id, node) in &update.nodes {
            // egui gives a button its text as its label, a text label its text as its value.
            let (Some(label), Some(b)) = (node.label().or_else(|| node.value()), node.bounds())
            else {
                continue;
            };
            let o = js_sys::Object::new();
            let set = |k: &str, v: JsValue| {
                let _ = js_sys::Reflect::set(&o, &k.into(), &v);
            };
            set("id", id.0.to_string().into());
            set("label", label.into());
            set("role", format!("{:?}", node.role()).into());
            set("disabled", node.is_disabled().into());
            set("x", (b.x0 * scale).into());
            set("y", (b.y0 * scale).into());
            set("w", ((b.x1 - b.x0) * scale).into());
            set("h", ((b.y1 - b.y0) * scale).into());
            list.push(&o);
        }
        let _ = js_sys::Reflect::set(&js_sys::global(), &"texploreWidgets".into(), &list);
    }
}
