#pragma once
// What the reader and the writer of freeform_cad share: Open CASCADE's messages collected instead
// of printed, its unit setting for one transfer, file extensions. Private to freeform_cad.

#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_Printer.hxx>

namespace freeform::occt {

inline std::string lower(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

/// Collects Open CASCADE's messages (warnings and worse) while it is installed; Open CASCADE's own
/// printer to standard output is removed once, for good: the library never prints.
class CollectingPrinter : public Message_Printer {
public:
    explicit CollectingPrinter(std::vector<std::string>* out) : out_(out) { SetTraceLevel(Message_Warning); }

protected:
    void send(const TCollection_AsciiString& text, const Message_Gravity gravity) const override
    {
        if (gravity < Message_Warning) return;
        // Open CASCADE frames its messages in asterisks: "**** ERR StepFile : ... ****".
        std::string m = text.ToCString();
        const auto first = m.find_first_not_of("* \t\n"), last = m.find_last_not_of("* \t\n");
        if (first != std::string::npos) out_->push_back(m.substr(first, last - first + 1));
    }

private:
    std::vector<std::string>* out_;
};

class MessageScope {
public:
    MessageScope() : printer_(new CollectingPrinter(&messages))
    {
        const Handle(Message_Messenger)& m = Message::DefaultMessenger();
        m->RemovePrinters(STANDARD_TYPE(Message_Printer));
        m->AddPrinter(printer_);
    }
    ~MessageScope() { Message::DefaultMessenger()->RemovePrinter(printer_); }
    MessageScope(const MessageScope&) = delete;
    MessageScope& operator=(const MessageScope&) = delete;

    std::vector<std::string> messages;

    /// " (Open CASCADE: first message)" for an error text, or "".
    std::string firstMessage() const { return messages.empty() ? "" : " (Open CASCADE: " + messages.front() + ")"; }

private:
    Handle(Message_Printer) printer_;
};

/// Sets xstep.cascade.unit for one transfer (so coordinates stay in the file's unit) and puts
/// the old value back.
class CascadeUnit {
public:
    explicit CascadeUnit(const char* unit) : old_(Interface_Static::CVal("xstep.cascade.unit"))
    {
        Interface_Static::SetCVal("xstep.cascade.unit", unit);
    }
    ~CascadeUnit() { Interface_Static::SetCVal("xstep.cascade.unit", old_.c_str()); }
    CascadeUnit(const CascadeUnit&) = delete;
    CascadeUnit& operator=(const CascadeUnit&) = delete;

private:
    std::string old_;
};

} // namespace freeform::occt
