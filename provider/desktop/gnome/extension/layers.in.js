// What the extension shows: the field over a monitor and the mark where a
// phone points, each a non-reactive actor (it takes no pointer and no focus)
// with an image the provider wrote to its private folder. Part of
// extension.js (generate.cmake puts it in place of its marker).

// The soft edge of the focus circle, as the X11 overlay's: the field fades
// over the outer 15 % of the radius so its edge does not read as a border.
const FOCUS_SOFTNESS = 0.15;

// Sets the image at `path` as the actor's content; its size in pixels.
function loadImage(actor, path) {
    const pixbuf = GdkPixbuf.Pixbuf.new_from_file(path);
    const content = new St.ImageContent({preferred_width: pixbuf.width, preferred_height: pixbuf.height});
    const format = pixbuf.has_alpha ? Cogl.PixelFormat.RGBA_8888 : Cogl.PixelFormat.RGB_888;
    const args = [pixbuf.get_pixels(), format, pixbuf.width, pixbuf.height, pixbuf.rowstride];
    try {
        content.set_data(...args);
    } catch (e) {
        // GNOME 46+ wants the Cogl context first.
        content.set_data(global.stage.context.get_backend().get_cogl_context(), ...args);
    }
    actor.set_content(content);
    return [pixbuf.width, pixbuf.height];
}

// Only the field within a soft circle: a fragment mask over the actor.
const FocusEffect = GObject.registerClass(
class UmfFocusEffect extends Shell.GLSLEffect {
    vfunc_build_pipeline() {
        const hook = (Shell.SnippetHook ?? Cogl.SnippetHook).FRAGMENT;
        this.add_glsl_snippet(hook,
            'uniform vec2 umf_centre; uniform float umf_radius; uniform vec2 umf_size; uniform float umf_soft;',
            'float d = distance(cogl_tex_coord_in[0].xy * umf_size, umf_centre);\n' +
            'float inner = umf_radius * (1.0 - umf_soft);\n' +
            'float m = d <= inner ? 1.0 : clamp((umf_radius - d) / max(umf_radius - inner, 0.0001), 0.0, 1.0);\n' +
            'cogl_color_out *= m;',
            false);
    }

    setCircle(x, y, radius, width, height) {
        this.set_uniform_float(this.get_uniform_location('umf_centre'), 2, [x, y]);
        this.set_uniform_float(this.get_uniform_location('umf_radius'), 1, [radius]);
        this.set_uniform_float(this.get_uniform_location('umf_size'), 2, [width, height]);
        this.set_uniform_float(this.get_uniform_location('umf_soft'), 1, [FOCUS_SOFTNESS]);
        this.queue_repaint();
    }
});

// The field over one monitor: never reactive, so it takes no pointer and no
// focus; its opacity is the pulse, which costs a composite and no upload.
class FieldLayer {
    constructor(parent) {
        this.actor = new Clutter.Actor({reactive: false, visible: false, name: 'umf-field'});
        this.actor.set_content_scaling_filters(Clutter.ScalingFilter.NEAREST, Clutter.ScalingFilter.NEAREST);
        this.imageSize = [0, 0];
        this.focus = null;
        this.wanted = false;  // shown when not hidden for a snapshot
        parent.add_child(this.actor);
    }

    load(path) {
        this.imageSize = loadImage(this.actor, path);
        this._applyFocus();
    }

    cover(monitor) {
        this.actor.set_position(monitor.x, monitor.y);
        this.actor.set_size(monitor.width, monitor.height);
    }

    setFocus(circle) {
        this.focus = circle;
        this._applyFocus();
    }

    _applyFocus() {
        if (!this.focus) {
            this.actor.remove_effect_by_name('umf-focus');
            return;
        }
        let effect = this.actor.get_effect('umf-focus');
        if (!effect) {
            effect = new FocusEffect();
            this.actor.add_effect_with_name('umf-focus', effect);
        }
        const [x, y, radius] = this.focus;
        effect.setCircle(x, y, radius, this.imageSize[0], this.imageSize[1]);
    }

    destroy() {
        this.actor.destroy();
    }
}

// The ring and title where a phone points, at full strength whatever the
// field's pulse: an actor of its own above the field. Its image is in the
// monitor's physical pixels, as the field's, and placed by its top-left
// corner in them.
class AimMark {
    constructor(parent) {
        this.actor = new Clutter.Actor({reactive: false, visible: false, name: 'umf-aim-mark'});
        this.actor.set_content_scaling_filters(Clutter.ScalingFilter.NEAREST, Clutter.ScalingFilter.NEAREST);
        this.imageSize = [0, 0];
        this.corner = [0, 0];
        parent.add_child(this.actor);
    }

    load(path) {
        this.imageSize = loadImage(this.actor, path);
    }

    // `scale`: the monitor's physical pixels per logical one.
    place(monitor, scale, x, y) {
        this.corner = [x, y];
        this.actor.set_position(monitor.x + x / scale, monitor.y + y / scale);
        this.actor.set_size(this.imageSize[0] / scale, this.imageSize[1] / scale);
    }

    destroy() {
        this.actor.destroy();
    }
}
