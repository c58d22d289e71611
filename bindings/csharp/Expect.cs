// The checks' reporting, shared by Checks.cs and WalkerGround.cs (compiled
// into each test program, not part of the binding).
using System;

static class Expect
{
    public static int Failures;

    public static void That(string what, bool ok, string detail)
    {
        Console.WriteLine("{0}: {1} ({2})", ok ? "ok  " : "FAIL", what, detail);
        if (!ok) ++Failures;
    }

    // Runs `action`, expecting an exception of type T whose message contains `text`.
    public static void Throws<T>(string what, Action action, string text) where T : Exception
    {
        try
        {
            action();
            That(what, false, "no exception");
        }
        catch (T e)
        {
            That(what, e.Message.Contains(text), e.GetType().Name + ": " + e.Message);
        }
    }

    // The last line: "NAME: all passed" or "NAME: N failed"; the exit code.
    public static int Summary(string name)
    {
        Console.WriteLine(Failures == 0 ? name + ": all passed" : name + ": " + Failures + " failed");
        return Failures == 0 ? 0 : 1;
    }
}
