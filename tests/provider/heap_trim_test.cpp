// The provider gives memory back after many connections ended, and leaves a
// quiet heap alone (the flood benchmark in docs/BENCHMARKS.md measures it).
#ifdef UMF_PROVIDER_TESTS

#include "provider/net/heap_trim.hpp"

#include <gtest/gtest.h>

#include <memory>

#include "provider/net/connection_registry.hpp"

namespace {

using namespace umf::provider;

TEST(HeapTrimmer, TrimsOnlyAfterEnoughConnectionsEnded) {
    boost::asio::io_context io;
    auto registry = std::make_shared<ConnectionRegistry>();
    auto trimmer = std::make_shared<HeapTrimmer>(io, registry, std::chrono::milliseconds(10), 3);
    trimmer->start();
    io.run_for(std::chrono::milliseconds(60));
    EXPECT_EQ(trimmer->trims(), 0u) << "nothing ended: nothing to give back";

    // Three connections come and go (the registry only counts them).
    int slots[3];
    for (int& slot : slots) registry->add(reinterpret_cast<Connection*>(&slot), {});
    for (int& slot : slots) registry->remove(reinterpret_cast<Connection*>(&slot));
    EXPECT_EQ(registry->ended(), 3u);
    io.restart();
    io.run_for(std::chrono::milliseconds(60));
    EXPECT_EQ(trimmer->trims(), 1u) << "once for those three, not again while it stays quiet";

    trimmer->stop();
    io.restart();
    io.run_for(std::chrono::milliseconds(30));
    EXPECT_TRUE(io.stopped()) << "stop leaves the io_context no work";
}

}  // namespace

#endif
