// The one PDF file assembler: every cross-reference offset lands on its
// object, and the trailer names the catalog and, when given, the info.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "shared/io/pdf_objects.hpp"

namespace {

TEST(PdfObjects, TheCrossReferencesPointAtTheirObjects) {
    const std::string pdf = umf::io::pdf_from_objects({"<< /Type /Catalog /Pages 2 0 R >>",
                                                       "<< /Type /Pages /Kids [] /Count 0 >>", "<< /Title (x) >>"},
                                                      3);
    EXPECT_EQ(pdf.rfind("%PDF-1.4\n", 0), 0u);
    const auto xref = pdf.find("xref\n0 4\n0000000000 65535 f \n");
    ASSERT_NE(xref, std::string::npos);
    for (int i = 1; i <= 3; ++i) {
        const std::string entry = pdf.substr(xref + 9 + 20 * static_cast<std::size_t>(i), 20);
        const std::size_t offset = std::strtoull(entry.c_str(), nullptr, 10);
        EXPECT_EQ(pdf.compare(offset, std::to_string(i).size() + 6, std::to_string(i) + " 0 obj"), 0) << i;
    }
    EXPECT_NE(pdf.find("trailer\n<< /Size 4 /Root 1 0 R /Info 3 0 R >>\nstartxref\n" + std::to_string(xref) +
                       "\n%%EOF\n"),
              std::string::npos);
    EXPECT_EQ(umf::io::pdf_from_objects({"<< /Type /Catalog >>"}).find("/Info"), std::string::npos);
}

}  // namespace
