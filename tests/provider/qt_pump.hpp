// Tests of Qt windows wait by running the event loop: timers, repaints and
// the window system's events only happen while it runs.
#pragma once

#include <QCoreApplication>
#include <QElapsedTimer>
#include <chrono>
#include <thread>

namespace umf::test {

// Runs the event loop until `done` or the timeout; whether `done` came.
template <class Predicate>
bool pump_until(Predicate done, int timeout_ms) {
    QElapsedTimer clock;
    clock.start();
    while (!done()) {
        if (clock.elapsed() > timeout_ms) return false;
        QCoreApplication::processEvents(QEventLoop::AllEvents, 5);
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return true;
}

}  // namespace umf::test
