// The umf GNOME Shell extension: what the umf provider cannot do from outside
// Mutter (there is no layer shell, no screencopy and no window list for
// clients): the field drawn above every window, the window under a point,
// snapshots without the portal's prompt, moving a window. It answers on the
// session bus (org.umf.Shell1.xml) to the shell's own user only.
//
// One source for GNOME 43-44 (imports.*) and 45+ (ES modules): the build puts
// the imports and the entry point around this text (generate.cmake); nothing
// else differs.

/* @UMF_IMPORTS@ */

const BUS_NAME = 'org.umf.Shell1';
const OBJECT_PATH = '/org/umf/Shell1';
const ERROR_PREFIX = 'org.umf.Shell1.Error';
const API_VERSION = 2;
const IFACE_XML = `@UMF_DBUS_XML@`;
// The caller's uid, per unique bus name; those names are never reused on a
// bus, so an entry cannot go stale. Bounded for a long session.
const MAX_KNOWN_SENDERS = 256;

class RefusedError extends Error {}

// The provider's private folder, the only place files are read from or
// written to. Checked on each use: a real folder, the user's own, not
// writable by anyone else.
function privateFolder() {
    const path = GLib.build_filenamev([GLib.get_user_runtime_dir(), 'umf']);
    let info;
    try {
        info = Gio.File.new_for_path(path).query_info('standard::type,unix::uid,unix::mode',
            Gio.FileQueryInfoFlags.NOFOLLOW_SYMLINKS, null);
    } catch (e) {
        throw new RefusedError(`the private folder ${path} is missing`);
    }
    if (info.get_file_type() !== Gio.FileType.DIRECTORY)
        throw new RefusedError(`${path} is not a folder`);
    if (info.get_attribute_uint32('unix::uid') !== shellUid())
        throw new RefusedError(`${path} is not owned by the shell's user`);
    if ((info.get_attribute_uint32('unix::mode') & 0o022) !== 0)
        throw new RefusedError(`${path} is writable by group or others`);
    return path;
}

// A base name in the private folder: no path, no hidden file.
function privatePath(name) {
    if (typeof name !== 'string' || !/^[A-Za-z0-9_-][A-Za-z0-9_.-]{0,99}$/.test(name))
        throw new RefusedError(`not a plain file name: ${name}`);
    return GLib.build_filenamev([privateFolder(), name]);
}

// An existing regular file (no symbolic link) in the private folder.
function privateFileToRead(name) {
    const path = privatePath(name);
    let info;
    try {
        info = Gio.File.new_for_path(path).query_info('standard::type,unix::uid',
            Gio.FileQueryInfoFlags.NOFOLLOW_SYMLINKS, null);
    } catch (e) {
        throw new RefusedError(`no file ${path}`);
    }
    if (info.get_file_type() !== Gio.FileType.REGULAR || info.get_attribute_uint32('unix::uid') !== shellUid())
        throw new RefusedError(`${path} is not a regular file of the shell's user`);
    return path;
}

function shellUid() {
    return new Gio.Credentials().get_unix_user();
}

function plainRect(r) {
    return [r.x, r.y, r.width, r.height];
}

function nextFrame() {
    return new Promise(resolve => {
        let done = false;
        let handler = 0;
        const finish = () => {
            if (done)
                return;
            done = true;
            global.stage.disconnect(handler);
            resolve();
        };
        handler = global.stage.connect('after-paint', () => finish());
        global.stage.queue_redraw();
        // A stage that does not paint (no monitor) must not hold the caller.
        GLib.timeout_add(GLib.PRIORITY_DEFAULT, 250, () => {
            finish();
            return GLib.SOURCE_REMOVE;
        });
    });
}

/* @UMF_LAYERS@ */

// The service object behind org.umf.Shell1.
class UmfShell {
    enable() {
        this._fields = new Map();
        this._aimMarks = new Map();
        this._connectors = new Map();
        this._connectorsKnown = false;
        this._shellPid = new Gio.Credentials().get_unix_pid();
        this._senderUids = new Map();
        this._shots = 0;
        this._snapshotting = false;
        this._shooting = Promise.resolve();
        this._parent = Main.layoutManager.uiGroup;
        // Chrome added later (a modal dialog, a notification) goes on top of
        // the group: the fields are put back above it.
        const onChildAdded = (_group, child) => {
            if (!child || (child.name !== 'umf-field' && child.name !== 'umf-aim-mark'))
                this._raiseFields();
        };
        // 'actor-added' until Mutter 45 named it 'child-added'.
        try {
            this._childAdded = this._parent.connect('child-added', onChildAdded);
        } catch (e) {
            this._childAdded = this._parent.connect('actor-added', onChildAdded);
        }
        this._monitorsChanged = Main.layoutManager.connect('monitors-changed', () => this._relayout());
        this._exported = Gio.DBusExportedObject.wrapJSObject(IFACE_XML, this._methods());
        this._exported.export(Gio.DBus.session, OBJECT_PATH);
        this._nameId = Gio.bus_own_name_on_connection(Gio.DBus.session, BUS_NAME,
            Gio.BusNameOwnerFlags.REPLACE | Gio.BusNameOwnerFlags.ALLOW_REPLACEMENT, null, null);
        this._readConnectors();
    }

    disable() {
        if (this._nameId)
            Gio.bus_unown_name(this._nameId);
        this._nameId = 0;
        this._exported?.unexport();
        this._exported = null;
        Main.layoutManager.disconnect(this._monitorsChanged);
        this._parent.disconnect(this._childAdded);
        for (const layer of [...this._fields.values(), ...this._aimMarks.values()])
            layer.destroy();
        this._fields.clear();
        this._aimMarks.clear();
    }

    // The D-Bus methods, each as NameAsync(params, invocation) so that the
    // caller's uid can be asked for before anything is done.
    _methods() {
        const methods = {
            Version: () => new GLib.Variant('(us)', [API_VERSION, Config.PACKAGE_VERSION]),
            Monitors: async () => {
                // DisplayConfig may come up after the extension.
                if (!this._connectorsKnown)
                    await this._readConnectors();
                return new GLib.Variant('(a(siiiid))', [this._monitors()]);
            },
            WindowAt: ([x, y, pids, classes]) => this._windowAt(x, y, pids, classes),
            ListWindows: () => new GLib.Variant('(a(tisss(iiii)i))', [this._windows().map(w => this._describe(w))]),
            MoveWindow: ([id, x, y]) => new GLib.Variant('(b)', [this._move(id, x, y)]),
            Snapshot: ([x, y, width, height]) => this._queueSnapshot(x, y, width, height, false),
            ScreenAsShown: ([x, y, width, height]) => this._queueSnapshot(x, y, width, height, true),
            SetField: ([monitor, name]) => this._setField(monitor, name),
            SetFieldOpacity: ([monitor, opacity]) => this._withField(monitor, f => {
                f.actor.opacity = Math.round(255 * Math.min(1, Math.max(0, opacity)));
            }),
            SetFieldFocus: ([monitor, on, x, y, radius]) => this._withField(monitor,
                f => f.setFocus(on ? [x, y, Math.max(0, radius)] : null)),
            SetFieldVisible: ([monitor, visible]) => this._withField(monitor, f => {
                f.wanted = visible;
                f.actor.visible = visible && !this._snapshotting;
            }),
            DropField: ([monitor]) => {
                for (const layers of [this._fields, this._aimMarks]) {
                    layers.get(monitor)?.destroy();
                    layers.delete(monitor);
                }
                return null;
            },
            SetAimMark: ([monitor, name, x, y]) => this._setAimMark(monitor, name, x, y),
            DropAimMark: ([monitor]) => {
                this._aimMarks.get(monitor)?.destroy();
                this._aimMarks.delete(monitor);
                return null;
            },
            FieldState: () => new GLib.Variant('(a(ibub(iiii)(ii)))', [[...this._fields.entries()].map(([i, f]) => [
                i, f.actor.visible, f.actor.opacity, f.focus !== null,
                [f.actor.x, f.actor.y, f.actor.width, f.actor.height].map(Math.round), f.imageSize])]),
        };
        const wrapped = {};
        for (const [name, handler] of Object.entries(methods))
            wrapped[`${name}Async`] = (params, invocation) => this._answer(handler, params, invocation);
        return wrapped;
    }

    async _answer(handler, params, invocation) {
        try {
            await this._checkCaller(invocation.get_sender());
            const reply = await handler(params);
            invocation.return_value(reply ?? null);
        } catch (e) {
            const kind = e instanceof RefusedError ? 'Refused' : 'Failed';
            invocation.return_dbus_error(`${ERROR_PREFIX}.${kind}`, e.message ?? String(e));
        }
    }

    // The caller must be the shell's own user: another user on this bus (a
    // bus shared for accessibility, a misconfigured one) gets nothing.
    async _checkCaller(sender) {
        let uid = this._senderUids.get(sender);
        if (uid === undefined) {
            uid = await new Promise((resolve, reject) => {
                Gio.DBus.session.call('org.freedesktop.DBus', '/org/freedesktop/DBus', 'org.freedesktop.DBus',
                    'GetConnectionUnixUser', new GLib.Variant('(s)', [sender]), new GLib.VariantType('(u)'),
                    Gio.DBusCallFlags.NONE, 1000, null, (connection, result) => {
                        try {
                            resolve(connection.call_finish(result).deepUnpack()[0]);
                        } catch (e) {
                            reject(new RefusedError(`cannot tell who ${sender} is: ${e.message}`));
                        }
                    });
            });
            if (this._senderUids.size >= MAX_KNOWN_SENDERS)
                this._senderUids.clear();
            this._senderUids.set(sender, uid);
        }
        if (uid !== shellUid())
            throw new RefusedError(`uid ${uid} is not the shell's user`);
    }

    _monitors() {
        return Main.layoutManager.monitors.map(m => [
            this._connectors.get(`${m.x},${m.y}`) ?? `monitor-${m.index}`,
            m.x, m.y, m.width, m.height, m.geometry_scale]);
    }

    // The connectors' names (DP-1, Meta-0) are Mutter's DisplayConfig's, by
    // the logical monitors' places.
    _readConnectors() {
        return new Promise(resolve => Gio.DBus.session.call('org.gnome.Mutter.DisplayConfig', '/org/gnome/Mutter/DisplayConfig',
            'org.gnome.Mutter.DisplayConfig', 'GetCurrentState', null, null, Gio.DBusCallFlags.NONE, 2000, null,
            (connection, result) => {
                if (!this._exported) {
                    resolve();
                    return;
                }
                try {
                    const [, , logical] = connection.call_finish(result).deepUnpack();
                    this._connectors.clear();
                    for (const [x, y, , , , monitors] of logical) {
                        if (monitors.length > 0)
                            this._connectors.set(`${x},${y}`, monitors[0][0]);
                    }
                    this._connectorsKnown = true;
                } catch (e) {
                    this._connectorsKnown = false;
                    log(`umf: no connector names: ${e.message}`);
                }
                this._exported.emit_signal('MonitorsChanged', null);
                resolve();
            }));
    }

    _relayout() {
        const monitors = Main.layoutManager.monitors;
        for (const [index, field] of [...this._fields.entries()]) {
            if (index < monitors.length) {
                field.cover(monitors[index]);
            } else {
                field.destroy();
                this._fields.delete(index);
            }
        }
        for (const [index, mark] of [...this._aimMarks.entries()]) {
            if (index < monitors.length) {
                mark.place(monitors[index], this._scale(index), ...mark.corner);
            } else {
                mark.destroy();
                this._aimMarks.delete(index);
            }
        }
        this._readConnectors();
    }

    // The fields above every window, the aim marks above the fields.
    _raiseFields() {
        for (const layer of [...this._fields.values(), ...this._aimMarks.values()])
            this._parent.set_child_above_sibling(layer.actor, null);
    }

    // Physical pixels per logical one on a monitor: as its field's image
    // was made, else as Mutter scales it.
    _scale(monitor) {
        const field = this._fields.get(monitor);
        const logical = Main.layoutManager.monitors[monitor];
        if (field && field.imageSize[0] > 0)
            return field.imageSize[0] / logical.width;
        return logical.geometry_scale ?? 1;
    }

    // `name` empty: the mark already shown, moved.
    _setAimMark(monitor, name, x, y) {
        const monitors = Main.layoutManager.monitors;
        if (!Number.isInteger(monitor) || monitor < 0 || monitor >= monitors.length)
            throw new RefusedError(`no monitor ${monitor}`);
        let mark = this._aimMarks.get(monitor);
        if (!mark && name === '')
            throw new RefusedError(`no aim mark on monitor ${monitor}`);
        if (name !== '') {
            const path = privateFileToRead(name);
            if (!mark) {
                mark = new AimMark(this._parent);
                this._aimMarks.set(monitor, mark);
            }
            mark.load(path);
        }
        mark.place(monitors[monitor], this._scale(monitor), x, y);
        mark.actor.visible = !this._snapshotting;
        this._raiseFields();
        return null;
    }

    _withField(monitor, change) {
        const field = this._fields.get(monitor);
        if (!field)
            throw new RefusedError(`no field on monitor ${monitor}`);
        change(field);
        return null;
    }

    _setField(monitor, name) {
        const monitors = Main.layoutManager.monitors;
        if (!Number.isInteger(monitor) || monitor < 0 || monitor >= monitors.length)
            throw new RefusedError(`no monitor ${monitor}`);
        const path = privateFileToRead(name);
        let field = this._fields.get(monitor);
        if (!field) {
            field = new FieldLayer(this._parent);
            this._fields.set(monitor, field);
        }
        field.load(path);
        field.cover(monitors[monitor]);
        this._raiseFields();
        return null;
    }

    // Application windows as shown now, bottom to top.
    _windows() {
        const workspace = global.workspace_manager.get_active_workspace();
        // The shell's own X11 helper windows are not content.
        return global.get_window_actors().map(a => a.meta_window).filter(w => w && w.get_pid() !== this._shellPid &&
            w.get_window_type() !== Meta.WindowType.DESKTOP && !w.minimized && w.showing_on_its_workspace() &&
            (w.is_on_all_workspaces() || w.located_on_workspace(workspace)));
    }

    _describe(w) {
        const x11 = w.get_client_type() === Meta.WindowClientType.X11;
        return [w.get_id(), Math.max(0, w.get_pid() ?? 0), w.get_title() ?? '', w.get_wm_class() ?? '',
            x11 ? w.get_wm_class_instance() ?? '' : '', plainRect(w.get_frame_rect()), w.get_monitor()];
    }

    _windowAt(x, y, pids, classes) {
        const skipPids = new Set(pids);
        const skipClasses = new Set(classes);
        // In the overview windows are not where their frames say.
        const windows = Main.overview.visible ? [] : this._windows();
        for (let i = windows.length - 1; i >= 0; --i) {
            const w = windows[i];
            const r = w.get_frame_rect();
            if (x < r.x || y < r.y || x >= r.x + r.width || y >= r.y + r.height)
                continue;
            const [id, pid, title, wmClass, instance, rect, monitor] = this._describe(w);
            if (skipPids.has(pid) || skipClasses.has(wmClass) || (instance && skipClasses.has(instance)))
                continue;
            return new GLib.Variant('(b(tisss(iiii)i))', [true, [id, pid, title, wmClass, instance, rect, monitor]]);
        }
        return new GLib.Variant('(b(tisss(iiii)i))', [false, [0, 0, '', '', '', [0, 0, 0, 0], -1]]);
    }

    _move(id, x, y) {
        const window = global.get_window_actors().map(a => a.meta_window).find(w => w && w.get_id() === id);
        if (!window)
            return false;
        window.move_frame(true, x, y);
        return true;
    }

    // One snapshot at a time (Shell.Screenshot takes one at a time too).
    _queueSnapshot(x, y, width, height, withField) {
        const shot = this._shooting.then(() => this._snapshot(x, y, width, height, withField));
        this._shooting = shot.catch(() => {});
        return shot;
    }

    async _snapshot(x, y, width, height, withField) {
        const [stageWidth, stageHeight] = global.stage.get_size();
        const left = Math.max(0, x), top = Math.max(0, y);
        const right = Math.min(stageWidth, x + width), bottom = Math.min(stageHeight, y + height);
        if (right <= left || bottom <= top)
            throw new RefusedError(`the rectangle ${x},${y} ${width}x${height} is off the screen`);
        const name = `snapshot-${++this._shots}.png`;
        const file = Gio.File.new_for_path(privatePath(name));
        this._snapshotting = !withField;
        if (!withField) {
            for (const layer of [...this._fields.values(), ...this._aimMarks.values()])
                layer.actor.visible = false;
        }
        try {
            await nextFrame();
            const stream = file.replace(null, false, Gio.FileCreateFlags.PRIVATE | Gio.FileCreateFlags.REPLACE_DESTINATION, null);
            try {
                await new Promise((resolve, reject) => {
                    new Shell.Screenshot().screenshot_area(left, top, right - left, bottom - top, stream, (shooter, result) => {
                        try {
                            shooter.screenshot_area_finish(result);
                            resolve();
                        } catch (e) {
                            reject(e);
                        }
                    });
                });
            } finally {
                stream.close(null);
            }
        } finally {
            this._snapshotting = false;
            for (const field of this._fields.values())
                field.actor.visible = field.wanted;
            for (const mark of this._aimMarks.values())
                mark.actor.visible = true;
        }
        return new GLib.Variant('(s)', [name]);
    }
}

/* @UMF_ENTRY@ */
