// JsonWriter: structure, escaping, numbers (round trip, non-finite), misuse.
#include "core/json/JsonWriter.hpp"

#include "core/Error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>

using namespace regolith::core;

TEST(JsonWriter, NestedDocumentPrettyAndCompact) {
    auto build = [](JsonWriter& w) {
        w.beginObject()
            .member("scene", "gas")
            .member("ranks", 4)
            .member("ok", true)
            .key("timing_s")
            .beginObject()
            .member("sync", 0.5)
            .endObject()
            .member("momentum", Vec3(0, 1, -2.5))
            .key("empty")
            .beginArray()
            .endArray()
            .key("list")
            .beginArray()
            .value(1)
            .null()
            .endArray()
            .endObject();
    };
    JsonWriter pretty;
    build(pretty);
    EXPECT_EQ(pretty.str(), R"({
  "scene": "gas",
  "ranks": 4,
  "ok": true,
  "timing_s": {
    "sync": 0.5
  },
  "momentum": [0, 1, -2.5],
  "empty": [],
  "list": [
    1,
    null
  ]
}
)");
    JsonWriter compact(0);
    build(compact);
    EXPECT_EQ(compact.str(),
              "{\"scene\":\"gas\",\"ranks\":4,\"ok\":true,\"timing_s\":{\"sync\":0.5},"
              "\"momentum\":[0,1,-2.5],\"empty\":[],\"list\":[1,null]}\n");
}

TEST(JsonWriter, StringsAreEscapedAndAlwaysValidUtf8) {
    EXPECT_EQ(JsonWriter::quote("plain"), "\"plain\"");
    EXPECT_EQ(JsonWriter::quote("a\"b\\c/d"), R"("a\"b\\c/d")");
    EXPECT_EQ(JsonWriter::quote("\n\r\t\b\f"), R"("\n\r\t\b\f")");
    EXPECT_EQ(JsonWriter::quote(std::string_view("\x01\x1f\0", 3)), R"("\u0001\u001f\u0000")");
    EXPECT_EQ(JsonWriter::quote("h\u00e9llo \u2014 \U0001F600"),
              "\"h\u00e9llo \u2014 \U0001F600\"");
    EXPECT_EQ(JsonWriter::quote("bad\xff byte"), R"("bad\uFFFD byte")");
    EXPECT_EQ(JsonWriter::quote("\xc0\xaf"), R"("\uFFFD\uFFFD")");           // overlong '/'
    EXPECT_EQ(JsonWriter::quote("\xed\xa0\x80"), R"("\uFFFD\uFFFD\uFFFD")"); // surrogate
    EXPECT_EQ(JsonWriter::quote("\xe2\x80"), R"("\uFFFD\uFFFD")");           // truncated
    JsonWriter w;
    w.beginObject().member("k\"ey", "v\nal").endObject();
    EXPECT_EQ(w.str(), "{\n  \"k\\\"ey\": \"v\\nal\"\n}\n");
}

TEST(JsonWriter, NumbersRoundTripAndNonFiniteIsNull) {
    for (double const x : {0.1, 1.0 / 3.0, 6.674e-11, -1e300, 5e-324, 123456789.125,
                           std::numeric_limits<double>::max(), -0.0}) {
        std::string const s = JsonWriter::number(x);
        EXPECT_EQ(std::strtod(s.c_str(), nullptr), x) << s;
        EXPECT_EQ(s.find_first_not_of("0123456789+-.e"), std::string::npos) << s;
    }
    EXPECT_EQ(JsonWriter::number(0.1), "0.1");
    EXPECT_EQ(JsonWriter::number(std::numeric_limits<double>::quiet_NaN()), "null");
    EXPECT_EQ(JsonWriter::number(std::numeric_limits<double>::infinity()), "null");
    EXPECT_EQ(JsonWriter::number(-std::numeric_limits<double>::infinity()), "null");
    JsonWriter w(0);
    w.beginArray()
        .value(std::numeric_limits<std::int64_t>::min())
        .value(std::numeric_limits<std::uint64_t>::max())
        .value(std::nan(""))
        .value(false)
        .endArray();
    EXPECT_EQ(w.str(), "[-9223372036854775808,18446744073709551615,null,false]\n");
}

TEST(JsonWriter, MisuseThrows) {
    EXPECT_THROW(JsonWriter().beginObject().value(1), Error);             // value without key
    EXPECT_THROW(JsonWriter().beginArray().key("k"), Error);              // key in an array
    EXPECT_THROW(JsonWriter().beginObject().endArray(), Error);           // wrong end
    EXPECT_THROW(JsonWriter().beginObject().key("a").endObject(), Error); // dangling key
    EXPECT_THROW(JsonWriter().value(1).value(2), Error);                  // two documents
    EXPECT_THROW((void)JsonWriter().beginObject().str(), Error);          // unfinished
    EXPECT_THROW((void)JsonWriter().str(), Error);                        // empty
    EXPECT_EQ(JsonWriter().value("x").str(), "\"x\"\n");
}
