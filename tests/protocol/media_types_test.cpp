// The media types named for files: the provider's content and the
// requester's puts read them from the same table.
#include <gtest/gtest.h>

#include "shared/protocol/media_types.hpp"

namespace {

using umf::protocol::media_type_for;

TEST(MediaTypes, TheExtensionInAnyCaseNamesTheType) {
    EXPECT_EQ(media_type_for("report.PDF"), "application/pdf");
    EXPECT_EQ(media_type_for("photo.jpeg"), "image/jpeg");
    EXPECT_EQ(media_type_for("/home/a/sheet.xlsx"), "application/vnd.openxmlformats-officedocument.spreadsheetml.sheet");
    EXPECT_EQ(media_type_for("clip.tar.mp4"), "video/mp4");
}

TEST(MediaTypes, UnknownOrMissingExtensionsAreOctetStreams) {
    EXPECT_EQ(media_type_for("Makefile"), "application/octet-stream");
    EXPECT_EQ(media_type_for("archive.tar.xz"), "application/octet-stream");
    EXPECT_EQ(media_type_for(".pdf"), "application/octet-stream");  // a hidden file named "pdf"
    EXPECT_EQ(media_type_for("dir.pdf/README"), "application/octet-stream");
    EXPECT_EQ(media_type_for(""), "application/octet-stream");
    EXPECT_EQ(media_type_for("trailing."), "application/octet-stream");
}

}  // namespace
