// APT codec against byte sequences worked out by hand from the Thorlabs "Host-Controller
// Communications Protocol" document; unit scaling against the document's conversion table;
// the streaming decoder against garbage, partial and concatenated input (fixed-seed fuzz).
#include <QtTest>

#include <functional>
#include <random>

#include "devices/apt/apt_decoder.h"
#include "devices/apt/apt_message.h"
#include "devices/apt/stage_models.h"

namespace tst_apt_codec {

using namespace fovea::apt;
using Bytes = std::vector<std::uint8_t>;

namespace {
std::string hex(const Message& m) {
  return toHex(encode(m));
}
// Interleaves random byte runs (up to max_garbage bytes) with `count` messages from `make`
// and decodes the stream fed in random chunks; returns what was sent and what came out.
std::pair<std::vector<Message>, std::vector<Message>> fuzzDecoder(std::mt19937& rng, int count, int max_garbage,
                                                                  int max_chunk,
                                                                  const std::function<Message(std::mt19937&)>& make) {
  std::uniform_int_distribution<int> byte(0, 255), len(0, max_garbage);
  std::vector<Message> sent, got;
  Bytes stream;
  for (int i = 0; i < count; ++i) {
    for (int k = len(rng); k > 0; --k) stream.push_back(static_cast<std::uint8_t>(byte(rng)));
    sent.push_back(make(rng));
    const auto b = encode(sent.back());
    stream.insert(stream.end(), b.begin(), b.end());
  }
  StreamDecoder d;
  for (std::size_t at = 0; at < stream.size();) {
    const std::size_t n = std::min<std::size_t>(stream.size() - at, 1 + rng() % static_cast<unsigned>(max_chunk));
    d.feed(std::span(stream).subspan(at, n));
    at += n;
    while (auto m = d.next()) got.push_back(*m);
  }
  return {sent, got};
}
// How many of `sent` come out of `got` in order.
std::size_t foundInOrder(const std::vector<Message>& sent, const std::vector<Message>& got) {
  std::size_t found = 0;
  for (const auto& m : got)
    if (found < sent.size() && m == sent[found]) ++found;
  return found;
}
UnitConverter converter(const char* controller, const char* stage) {
  return UnitConverter(*findController(controller), *findStage(stage));
}
}  // namespace

class TestAptCodec : public QObject {
  Q_OBJECT
 private slots:
  void headerOnlyMessages() {
    // Header-only: id (LE 16 bit), param1, param2, dest 0x50 (generic USB), source 0x01 (host).
    // MOD_IDENTIFY 0x0223 -> 23 02, params 00 00.
    QCOMPARE(hex(identify()), std::string("23 02 00 00 50 01"));
    // HW_REQ_INFO 0x0005.
    QCOMPARE(hex(reqHwInfo()), std::string("05 00 00 00 50 01"));
    // MOD_SET_CHANENABLESTATE 0x0210: param1 channel 1, param2 0x01 enable / 0x02 disable.
    QCOMPARE(hex(setChanEnableState(0x50, 1, true)), std::string("10 02 01 01 50 01"));
    QCOMPARE(hex(setChanEnableState(0x50, 1, false)), std::string("10 02 01 02 50 01"));
    QCOMPARE(hex(reqChanEnableState(0x50, 1)), std::string("11 02 01 00 50 01"));
    // HW_START_UPDATEMSGS 0x0011, HW_STOP_UPDATEMSGS 0x0012.
    QCOMPARE(hex(startUpdateMsgs(0x50)), std::string("11 00 00 00 50 01"));
    QCOMPARE(hex(stopUpdateMsgs(0x50)), std::string("12 00 00 00 50 01"));
    // MOT_MOVE_HOME 0x0443, channel 1.
    QCOMPARE(hex(moveHome(0x50, 1)), std::string("43 04 01 00 50 01"));
    // MOT_MOVE_JOG 0x046A: param2 direction 0x01 forward, 0x02 reverse.
    QCOMPARE(hex(moveJog(0x50, 1, JogDirection::Forward)), std::string("6A 04 01 01 50 01"));
    QCOMPARE(hex(moveJog(0x50, 1, JogDirection::Reverse)), std::string("6A 04 01 02 50 01"));
    // MOT_MOVE_STOP 0x0465: param2 stop mode 0x01 immediate, 0x02 profiled.
    QCOMPARE(hex(moveStop(0x50, 1, StopMode::Immediate)), std::string("65 04 01 01 50 01"));
    QCOMPARE(hex(moveStop(0x50, 1, StopMode::Profiled)), std::string("65 04 01 02 50 01"));
    // MOT_REQ_DCSTATUSUPDATE 0x0490, MOT_ACK_DCSTATUSUPDATE 0x0492 (keep-alive).
    QCOMPARE(hex(reqDcStatusUpdate(0x50, 1)), std::string("90 04 01 00 50 01"));
    QCOMPARE(hex(ackDcStatusUpdate(0x50)), std::string("92 04 00 00 50 01"));
    QCOMPARE(hex(reqVelParams(0x50, 1)), std::string("14 04 01 00 50 01"));
    QCOMPARE(hex(reqJogParams(0x50, 1)), std::string("17 04 01 00 50 01"));
    // A bay of a rack: destination 0x21 (bay 0).
    QCOMPARE(hex(moveHome(0x21, 1)), std::string("43 04 01 00 21 01"));
  }

  void longMessages() {
    // MOT_MOVE_ABSOLUTE 0x0453, 6 data bytes: header 53 04 | 06 00 | 0x50|0x80 = D0 | 01.
    // 5 mm on an MTS25-Z8: 5 x 34 304 = 171 520 = 0x00029E00 -> LE 00 9E 02 00; channel 01 00.
    const auto z8 = converter("KDC101", "MTS25-Z8");
    QCOMPARE(hex(moveAbsolute(0x50, 1, z8.positionToCounts(5.0))), std::string("53 04 06 00 D0 01 01 00 00 9E 02 00"));
    // MOT_MOVE_RELATIVE 0x0448 by -1 mm: -34 304 = 0x100000000 - 0x8600 = 0xFFFF7A00 -> 00 7A FF FF.
    QCOMPARE(hex(moveRelative(0x50, 1, z8.positionToCounts(-1.0))), std::string("48 04 06 00 D0 01 01 00 00 7A FF FF"));
    // MOT_SET_VELPARAMS 0x0413, 14 bytes (0x0E): channel, min velocity, acceleration, max velocity.
    // 1.5 mm/s^2 x 261.93 = 392.9 -> 393 = 0x189; 2.0 mm/s x 767 367.49 = 1 534 735 = 0x176B0F.
    VelParams v{1, 0, z8.accelerationToApt(1.5), z8.velocityToApt(2.0)};
    QCOMPARE(hex(setVelParams(0x50, v)), std::string("13 04 0E 00 D0 01 01 00 00 00 00 00 89 01 00 00 0F 6B 17 00"));
    // MOT_SET_JOGPARAMS 0x0416, 22 bytes (0x16): channel, mode 2 (single step), step 0.5 mm =
    // 17 152 = 0x4300, min velocity 0, acceleration 393, max velocity 1 534 735, stop mode 2.
    JogParams j{1, JogMode::SingleStep, z8.positionToCounts(0.5), 0, 393, 1534735, StopMode::Profiled};
    QCOMPARE(hex(setJogParams(0x50, j)),
             std::string("16 04 16 00 D0 01 01 00 02 00 00 43 00 00 00 00 00 00 89 01 00 00 0F 6B 17 00 02 00"));
    QCOMPARE(parseJogParams(setJogParams(0x50, j)).value(), j);
    QCOMPARE(parseVelParams(setVelParams(0x50, v)).value(), v);
  }

  void controllerReplies() {
    // MOT_MOVE_COMPLETED from the controller: dest host|0x80 = 81, source 50, 14 bytes:
    // channel 01 00, position 171 520 (00 9E 02 00), velocity 00 00, reserved 00 00,
    // status bits 0x80000400 (channel enabled + homed) -> 00 04 00 80.
    const Bytes raw = {0x64, 0x04, 0x0E, 0x00, 0x81, 0x50, 0x01, 0x00, 0x00, 0x9E,
                       0x02, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x04, 0x00, 0x80};
    StreamDecoder d;
    d.feed(raw);
    auto m = d.next();
    QVERIFY(m.has_value());
    QCOMPARE(m->id, id::kMotMoveCompleted);
    QCOMPARE(m->source, std::uint8_t{0x50});
    QCOMPARE(m->dest, std::uint8_t{0x01});
    auto s = parseChannelStatus(*m);
    QVERIFY(s.has_value());
    QCOMPARE(s->position, 171520);
    QCOMPARE(s->bits, status::kChannelEnabled | status::kHomed);
    QCOMPARE(encode(moveCompleted(0x50, *s)), raw);
    // Negative velocity words are signed: 0xFFFE = -2.
    ChannelStatus neg{1, -5, -2, status::kMovingReverse};
    QCOMPARE(parseChannelStatus(getDcStatusUpdate(0x50, neg)).value(), neg);
    // Stepper layout (GET_STATUSUPDATE 0x0481): position then a 32-bit encoder count.
    ChannelStatus st{1, -136533, 123456, status::kHomed};
    QCOMPARE(hex(getStatusUpdate(0x50, st)).substr(0, 17), std::string("81 04 0E 00 81 50"));
    QCOMPARE(parseChannelStatus(getStatusUpdate(0x50, st)).value(), st);
    // HW_GET_INFO: 84 (0x54) data bytes.
    HwInfo info;
    info.serial = 27000001;
    info.model = "KDC101";
    info.notes = "virtual";
    info.fw_major = 3;
    const Bytes enc = encode(getHwInfo(0x50, info));
    QCOMPARE(enc.size(), std::size_t{90});
    QCOMPARE(toHex(std::span(enc).first(10)),
             std::string("06 00 54 00 81 50 C1 FC 9B 01"));  // 27000001 = 0x019BFCC1 -> LE C1 FC 9B 01
    QCOMPARE(parseHwInfo(getHwInfo(0x50, info)).value(), info);
    // Parsers reject wrong lengths.
    Message shortInfo = getHwInfo(0x50, info);
    shortInfo.data.pop_back();
    QVERIFY(!parseHwInfo(shortInfo).has_value());
  }

  void unitScalingMatchesDocumentTable() {
    // KDC101, T = 2048/6e6 s: Z8 -> 767 367.49 per mm/s, 261.93 per mm/s^2.
    const auto z8 = converter("KDC101", "MTS25-Z8");
    QVERIFY(std::abs(z8.velocityScale() - 767367.49) < 0.01);
    QVERIFY(std::abs(z8.accelerationScale() - 261.93) < 0.005);
    // KBD101, T = 102.4 us, DDS 2 000 counts/mm -> 13 421.77 per mm/s, 1.374 per mm/s^2.
    const auto dds = converter("KBD101", "DDSM50");
    QVERIFY(std::abs(dds.velocityScale() - 13421.77) < 0.01);
    QVERIFY(std::abs(dds.accelerationScale() - 1.37439) < 1e-4);
    // K10CR1 (stepper): 136 533.33 counts/deg, 7 329 109 per deg/s, 1 502 per deg/s^2.
    const auto rot = converter("K10CR1", "K10CR1");
    QCOMPARE(rot.positionToCounts(1.0), 136533);
    QCOMPARE(rot.positionToCounts(90.0), 12288000);  // exact: 409 600 x 30
    QVERIFY(std::abs(rot.velocityScale() - 7329109.3) < 1.0);
    QVERIFY(std::abs(rot.accelerationScale() - 1502.0) < 0.5);
    // Round trips stay within half a count.
    QVERIFY(std::abs(z8.countsToPosition(z8.positionToCounts(12.3456)) - 12.3456) < 0.5 / 34304);
    QCOMPARE(controllerForSerial("27000001")->name, std::string("KDC101"));
    QCOMPARE(controllerForSerial("55000001")->name, std::string("K10CR1"));
    QVERIFY(!controllerForSerial("99000001").has_value());
  }

  void decoderHandlesPartialAndConcatenated() {
    Bytes stream;
    std::vector<Message> sent = {identify(), moveAbsolute(0x50, 1, 171520), moveHome(0x50, 1),
                                 setVelParams(0x50, VelParams{1, 0, 393, 1534735})};
    for (const auto& m : sent) {
      auto b = encode(m);
      stream.insert(stream.end(), b.begin(), b.end());
    }
    // Byte by byte.
    StreamDecoder d;
    std::vector<Message> got;
    for (auto b : stream) {
      d.feed(std::span(&b, 1));
      while (auto m = d.next()) got.push_back(*m);
    }
    QCOMPARE(got, sent);
    QCOMPARE(d.discardedBytes(), std::size_t{0});
    // All at once.
    StreamDecoder d2;
    d2.feed(stream);
    got.clear();
    while (auto m = d2.next()) got.push_back(*m);
    QCOMPARE(got, sent);
    // A partial long message waits for its data.
    StreamDecoder d3;
    auto abs = encode(moveAbsolute(0x50, 1, 42));
    d3.feed(std::span(abs).first(8));
    QVERIFY(!d3.next().has_value());
    d3.feed(std::span(abs).subspan(8));
    QCOMPARE(parseMoveAbsolute(*d3.next())->value, 42);
  }

  void decoderResynchronisesAfterGarbage() {
    StreamDecoder d;
    // Garbage that contains a near-miss: a real id with an impossible destination.
    Bytes garbage = {0xFF, 0x00, 0x53, 0x04, 0x06, 0x00, 0x7E, 0x01, 0x13};
    d.feed(garbage);
    auto home = encode(moveHome(0x50, 1));
    d.feed(home);
    auto m = d.next();
    QVERIFY(m.has_value());
    QCOMPARE(m->id, id::kMotMoveHome);
    QCOMPARE(d.discardedBytes(), garbage.size());
  }

  void decoderFuzzFixedSeed() {
    std::mt19937 rng(20261123);
    std::uniform_int_distribution<int> byte(0, 255);
    const auto [sent, got] = fuzzDecoder(rng, 3000, 40, 97, [](std::mt19937& g) {
      switch (g() % 6) {
        case 0:
          return moveAbsolute(0x50, 1, static_cast<std::int32_t>(g()));
        case 1:
          return moveHome(0x50, 1);
        case 2:
          return getDcStatusUpdate(
              0x50, ChannelStatus{1, static_cast<std::int32_t>(g()), 3, static_cast<std::uint32_t>(g())});
        case 3:
          return setJogParams(0x50, JogParams{});
        case 4:
          return moveStop(0x50, 1, StopMode::Immediate);
        default:
          return reqHwInfo();
      }
    });
    // Random bytes must never crash and every real message must come out in order (an
    // extremely rare fake header from noise is tolerated but counted).
    QCOMPARE(foundInOrder(sent, got), sent.size());
    QVERIFY2(got.size() - sent.size() <= 3, "noise produced too many fake messages");
    // Pure noise: no crash, nearly everything discarded.
    StreamDecoder noise;
    Bytes junk(200000);
    for (auto& b : junk) b = static_cast<std::uint8_t>(byte(rng));
    noise.feed(junk);
    std::size_t fakes = 0;
    while (noise.next()) ++fakes;
    QVERIFY(fakes <= 3);
    QVERIFY(noise.buffered() < 6 + StreamDecoder::kMaxDataLength);
  }

  void headerOnlyMovesAndParameterMessages() {
    // Header-only MOVE_ABSOLUTE / MOVE_RELATIVE (channel in param1): valid protocol, decoded whole.
    QCOMPARE(hex(moveAbsoluteStored(0x50, 1)), std::string("53 04 01 00 50 01"));
    QCOMPARE(hex(moveRelativeStored(0x50, 1)), std::string("48 04 01 00 50 01"));
    QVERIFY(acceptsLength(id::kMotMoveAbsolute, 0) && acceptsLength(id::kMotMoveAbsolute, 6));
    QVERIFY(!acceptsLength(id::kMotMoveAbsolute, 4));
    StreamDecoder d;
    d.feed(encode(moveAbsoluteStored(0x50, 1)));
    d.feed(encode(moveRelativeStored(0x50, 1)));
    auto a = d.next(), b = d.next();
    QVERIFY(a && b);
    QVERIFY(isStoredMove(*a) && isStoredMove(*b));
    QCOMPARE(a->param1, std::uint8_t{1});
    QVERIFY(!parseMoveAbsolute(*a));  // no counts in the header-only form
    // SET_MOVEABSPARAMS: 50 04 06 00 D0 01 | chan 01 00 | position 00 9E 02 00 (5 mm on a Z8).
    QCOMPARE(hex(setMoveAbsParams(0x50, 1, 171520)), std::string("50 04 06 00 D0 01 01 00 00 9E 02 00"));
    QCOMPARE(parseMoveParams(setMoveRelParams(0x50, 1, -34304))->value, -34304);
    // SET_HOMEPARAMS (14 bytes: chan, direction, limit switch, velocity, offset).
    QCOMPARE(hex(setHomeParams(0x50, HomeParams{1, 2, 1, 767367, 34304})),
             std::string("40 04 0E 00 D0 01 01 00 02 00 01 00 87 B5 0B 00 00 86 00 00"));
    // SET_LIMSWITCHPARAMS (16 bytes: chan, CW hard, CCW hard, CW soft, CCW soft, soft mode).
    QCOMPARE(hex(setLimSwitchParams(0x50, LimitSwitchParams{1, 3, 3, 0, 0, 1})),
             std::string("23 04 10 00 D0 01 01 00 03 00 03 00 00 00 00 00 00 00 00 00 01 00"));
    const auto l = parseLimSwitchParams(getLimSwitchParams(0x50, LimitSwitchParams{1, 2, 3, 5, 6, 1}));
    QVERIFY(l && l->cw_hard == 2 && l->ccw_hard == 3 && l->cw_soft == 5 && l->ccw_soft == 6);
    QCOMPARE(parseHomeParams(getHomeParams(0x50, HomeParams{1, 1, 4, 99, -7}))->offset, -7);
  }

  void controllerErrorResponses() {
    // HW_RICHRESPONSE: 81 00 44 00 81 50 | msg ident 53 04 | code 11 00 | 64 chars of text.
    const Message rich = hwRichResponse(0x50, ControllerResponse{0x0453, 0x0011, "Motor drive fault", true});
    const std::string h = hex(rich);
    QVERIFY2(h.rfind("81 00 44 00 81 50 53 04 11 00 4D 6F 74 6F 72", 0) == 0, h.c_str());
    QCOMPARE(encode(rich).size(), std::size_t{74});
    const auto r = parseControllerResponse(rich);
    QVERIFY(r && r->rich && r->code == 0x11 && r->message_id == id::kMotMoveAbsolute);
    QCOMPARE(describe(*r), std::string("code 0x0011 (17) after MOT_MOVE_ABSOLUTE: Motor drive fault"));
    // HW_RESPONSE: header only, the code in param1/param2.
    const auto plain = parseControllerResponse(hwResponse(0x50, 0x0203));
    QVERIFY(plain && !plain->rich && plain->code == 0x0203);
    QCOMPARE(describe(*plain), std::string("code 0x0203 (515): HW_RESPONSE, no text"));
    // Non-printable bytes in the controller's text never reach the user raw.
    Message noisy = rich;
    noisy.data[4] = 0x07;
    QCOMPARE(describe(*parseControllerResponse(noisy)),
             std::string("code 0x0011 (17) after MOT_MOVE_ABSOLUTE: otor drive fault"));
    QVERIFY(!parseControllerResponse(moveHome(0x50, 1)));
  }

  void channelIdentsAsBitMasks() {
    QCOMPARE(channelIdent(1, false), std::uint8_t{1});
    QCOMPARE(channelIdent(3, false), std::uint8_t{3});
    QCOMPARE(channelIdent(2, true), std::uint8_t{0x02});
    QCOMPARE(channelIdent(3, true), std::uint8_t{0x04});
    QCOMPARE(channelIdent(4, true), std::uint8_t{0x08});
  }

  void decoderRecoversEveryMessageAfterGarbage() {
    // Random byte runs interleaved with every valid header form (long, header-only,
    // header-only moves, both completion forms, error reports): every valid message that
    // follows a run of garbage comes out, in order, whatever the chunking.
    std::mt19937 rng(424242);
    const auto [sent, got] = fuzzDecoder(rng, 4000, 64, 61, [](std::mt19937& g) {
      switch (g() % 9) {
        case 0:
          return moveAbsoluteStored(0x50, 1);
        case 1:
          return moveRelativeStored(0x50, 1);
        case 2:
          return moveCompleted(0x50, ChannelStatus{1, static_cast<std::int32_t>(g()), 0, 0x80000030});
        case 3: {
          Message m = moveCompleted(0x50, ChannelStatus{});
          m.data.clear();  // header-only completion (old firmware)
          return m;
        }
        case 4:
          return hwRichResponse(0x50, ControllerResponse{0x0453, 7, "error text", true});
        case 5:
          return hwResponse(0x50, 3);
        case 6:
          return getStatusUpdate(0x50, ChannelStatus{1, 5, 5, 0x80000400});
        case 7:
          return setMoveAbsParams(0x50, 1, static_cast<std::int32_t>(g()));
        default:
          return getLimSwitchParams(0x50, LimitSwitchParams{});
      }
    });
    QCOMPARE(foundInOrder(sent, got), sent.size());
    QVERIFY2(got.size() - sent.size() <= 2, "noise produced too many fake messages");
  }
};

QTEST_GUILESS_MAIN(TestAptCodec)

}  // namespace tst_apt_codec
#include "tst_apt_codec.moc"
