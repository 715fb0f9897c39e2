// xdnd_drop WINDOW X Y PATH...: drops files on an X window as a file manager does, through the X
// server's drag-and-drop protocol (XDND version 5, freedesktop.org): XdndEnter offering
// text/uri-list, XdndPosition at (X, Y) in the window, XdndDrop once the target accepts, the
// uri-list handed over when the target asks for the XdndSelection, then XdndFinished awaited.
// For editor/tests/x11/drop_window.sh (the editor's GLFW window receives a real drop). Exit 0 when
// the target finished the drop and accepted it, 1 otherwise (a message on stderr); 10 s at most.

#include <X11/Xatom.h>
#include <X11/Xlib.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>

namespace {

std::string uriList(int count, char** paths)
{
    // RFC 2483: file URIs, CRLF after each; unreserved characters and '/' as they are.
    static const char* hex = "0123456789ABCDEF";
    std::string list;
    for (int i = 0; i < count; ++i) {
        list += "file://";
        for (const char* c = paths[i]; *c; ++c) {
            const unsigned char u = static_cast<unsigned char>(*c);
            if (std::isalnum(u) || std::strchr("/-_.~", u)) list += *c;
            else {
                list += '%';
                list += hex[u >> 4];
                list += hex[u & 15];
            }
        }
        list += "\r\n";
    }
    return list;
}

void send(Display* d, Window target, Atom type, long l0, long l1, long l2, long l3, long l4)
{
    XEvent e;
    std::memset(&e, 0, sizeof e);
    e.xclient.type = ClientMessage;
    e.xclient.display = d;
    e.xclient.window = target;
    e.xclient.message_type = type;
    e.xclient.format = 32;
    e.xclient.data.l[0] = l0;
    e.xclient.data.l[1] = l1;
    e.xclient.data.l[2] = l2;
    e.xclient.data.l[3] = l3;
    e.xclient.data.l[4] = l4;
    XSendEvent(d, target, False, NoEventMask, &e);
    XFlush(d);
}

} // namespace

int main(int argc, char** argv)
{
    if (argc < 5) {
        std::fprintf(stderr, "usage: xdnd_drop WINDOW X Y PATH...\n");
        return 2;
    }
    Display* d = XOpenDisplay(nullptr);
    if (!d) {
        std::fprintf(stderr, "xdnd_drop: cannot open the display\n");
        return 1;
    }
    const Window target = static_cast<Window>(std::strtoul(argv[1], nullptr, 0));
    const int x = std::atoi(argv[2]), y = std::atoi(argv[3]);
    const std::string data = uriList(argc - 4, argv + 4);

    const Atom aware = XInternAtom(d, "XdndAware", False), enter = XInternAtom(d, "XdndEnter", False),
               position = XInternAtom(d, "XdndPosition", False), status = XInternAtom(d, "XdndStatus", False),
               drop = XInternAtom(d, "XdndDrop", False), finished = XInternAtom(d, "XdndFinished", False),
               leave = XInternAtom(d, "XdndLeave", False), selection = XInternAtom(d, "XdndSelection", False),
               copy = XInternAtom(d, "XdndActionCopy", False), uriType = XInternAtom(d, "text/uri-list", False);

    // The target must say it speaks XDND (GLFW sets XdndAware on its windows).
    Atom actualType = None;
    int actualFormat = 0;
    unsigned long items = 0, after = 0;
    unsigned char* prop = nullptr;
    if (XGetWindowProperty(d, target, aware, 0, 1, False, XA_ATOM, &actualType, &actualFormat, &items, &after, &prop) != Success ||
        items == 0) {
        std::fprintf(stderr, "xdnd_drop: window 0x%lx has no XdndAware property\n", target);
        return 1;
    }
    const long version = std::min<long>(5, static_cast<long>(*reinterpret_cast<Atom*>(prop)));
    XFree(prop);

    const Window source = XCreateSimpleWindow(d, DefaultRootWindow(d), 0, 0, 1, 1, 0, 0, 0);
    XSetSelectionOwner(d, selection, source, CurrentTime);
    Window child = None;
    int rootX = 0, rootY = 0;
    XTranslateCoordinates(d, target, DefaultRootWindow(d), x, y, &rootX, &rootY, &child);

    send(d, target, enter, static_cast<long>(source), version << 24, static_cast<long>(uriType), None, None);
    send(d, target, position, static_cast<long>(source), 0, (long(rootX) << 16) | (rootY & 0xffff), CurrentTime, static_cast<long>(copy));

    bool accepted = false, dropped = false, delivered = false;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (std::chrono::steady_clock::now() < deadline) {
        if (!XPending(d)) {
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
            continue;
        }
        XEvent e;
        XNextEvent(d, &e);
        if (e.type == ClientMessage && e.xclient.message_type == status && !dropped) {
            accepted = (e.xclient.data.l[1] & 1) != 0;
            if (!accepted) {
                send(d, target, leave, static_cast<long>(source), 0, 0, 0, 0);
                std::fprintf(stderr, "xdnd_drop: the target refused the drop\n");
                return 1;
            }
            send(d, target, drop, static_cast<long>(source), 0, CurrentTime, 0, 0);
            dropped = true;
        } else if (e.type == SelectionRequest) {
            // The target asks for the data: the uri-list into its property.
            const XSelectionRequestEvent& r = e.xselectionrequest;
            XEvent reply;
            std::memset(&reply, 0, sizeof reply);
            reply.xselection.type = SelectionNotify;
            reply.xselection.display = d;
            reply.xselection.requestor = r.requestor;
            reply.xselection.selection = r.selection;
            reply.xselection.target = r.target;
            reply.xselection.time = r.time;
            reply.xselection.property = None;
            if (r.target == uriType) {
                XChangeProperty(d, r.requestor, r.property, uriType, 8, PropModeReplace,
                                reinterpret_cast<const unsigned char*>(data.data()), static_cast<int>(data.size()));
                reply.xselection.property = r.property;
                delivered = true;
            }
            XSendEvent(d, r.requestor, False, NoEventMask, &reply);
            XFlush(d);
        } else if (e.type == ClientMessage && e.xclient.message_type == finished) {
            // XDND 5 puts the accept flag in bit 0 of l[1]; GLFW 3.3 puts the byte count of the
            // data it read there, so any non-zero value is taken as accepted (the test script
            // checks what the editor did with the files through its --state anyway).
            const bool ok = delivered && (version < 5 || e.xclient.data.l[1] != 0);
            XDestroyWindow(d, source);
            XCloseDisplay(d);
            if (!ok) std::fprintf(stderr, "xdnd_drop: the target finished without taking the data (data %s, l[1] %ld)\n", delivered ? "handed over" : "never asked for", e.xclient.data.l[1]);
            return ok ? 0 : 1;
        }
    }
    std::fprintf(stderr, "xdnd_drop: no %s within 10 s\n", !accepted ? "XdndStatus" : !delivered ? "request for the data" : "XdndFinished");
    return 1;
}
