using System;
using System.Collections.Generic;
using System.Collections.Immutable;
using System.IO;
using System.Linq;
using System.Reflection;
using System.Reflection.Emit;
using System.Reflection.Metadata;
using System.Reflection.Metadata.Ecma335;
using System.Reflection.PortableExecutable;

namespace ParticlePhysics.Tests.Support;

/// <summary>
/// Reads the built core assembly's metadata and IL (System.Reflection.Metadata): which of its own types each type
/// uses, and which members of other assemblies it calls, so that tests can check its layering and its portability.
/// </summary>
internal sealed class CoreMetadata : IDisposable
{
    private static readonly Dictionary<ushort, OperandType> _operandTypes = typeof(OpCodes)
        .GetFields(BindingFlags.Public | BindingFlags.Static)
        .Select(f => (OpCode)f.GetValue(null)!)
        .ToDictionary(o => (ushort)o.Value, o => o.OperandType);

    private readonly FileStream _stream;
    private readonly PEReader _pe;

    public CoreMetadata()
        : this(typeof(ParticleWorld).Assembly)
    {
    }

    /// <summary>Reads another of the product's assemblies (the scene loader).</summary>
    public CoreMetadata(Assembly assembly)
    {
        _stream = File.OpenRead(assembly.Location);
        _pe = new PEReader(_stream);
        Reader = _pe.GetMetadataReader();
    }

    public MetadataReader Reader { get; }

    public void Dispose()
    {
        _pe.Dispose();
        _stream.Dispose();
    }

    /// <summary>The namespace of a type, that of its outermost declaring type for a nested one.</summary>
    public string NamespaceOf(TypeDefinitionHandle handle)
    {
        var type = Reader.GetTypeDefinition(handle);
        while (type.IsNested)
        {
            type = Reader.GetTypeDefinition(type.GetDeclaringType());
        }

        return Reader.GetString(type.Namespace);
    }

    public string NameOf(TypeDefinitionHandle handle)
    {
        var type = Reader.GetTypeDefinition(handle);
        var name = Reader.GetString(type.Name);
        return type.IsNested ? NameOf(type.GetDeclaringType()) + "+" + name : NamespaceOf(handle) + "." + name;
    }

    /// <summary>The types of this assembly (with their namespace) that <paramref name="handle"/> uses anywhere.</summary>
    public IReadOnlyCollection<TypeDefinitionHandle> TypesUsedBy(TypeDefinitionHandle handle)
    {
        var used = new TypeCollector(Reader);
        var type = Reader.GetTypeDefinition(handle);
        if (!type.BaseType.IsNil)
        {
            used.AddEntity(type.BaseType);
        }

        foreach (var implementation in type.GetInterfaceImplementations())
        {
            used.AddEntity(Reader.GetInterfaceImplementation(implementation).Interface);
        }

        foreach (var fieldHandle in type.GetFields())
        {
            Reader.GetFieldDefinition(fieldHandle).DecodeSignature(used, null);
        }

        foreach (var methodHandle in type.GetMethods())
        {
            var method = Reader.GetMethodDefinition(methodHandle);
            method.DecodeSignature(used, null);
            if (method.RelativeVirtualAddress != 0)
            {
                AddBody(_pe.GetMethodBody(method.RelativeVirtualAddress), used);
            }
        }

        used.Types.Remove(handle);
        return used.Types;
    }

    /// <summary>
    /// Every member of another assembly that the core references, with the type it returns (a field's type) and its
    /// whole signature, as text.
    /// </summary>
    public IEnumerable<(MemberReferenceHandle Handle, string Member, string Returns, string Signature)> ExternalMemberReferences()
    {
        var formatter = new SignatureFormatter();
        foreach (var handle in Reader.MemberReferences)
        {
            var member = Reader.GetMemberReference(handle);
            var parent = member.Parent.Kind switch
            {
                HandleKind.TypeReference => formatter.GetTypeFromReference(Reader, (TypeReferenceHandle)member.Parent, 0),
                HandleKind.TypeSpecification => Reader.GetTypeSpecification((TypeSpecificationHandle)member.Parent).DecodeSignature(formatter, null),
                _ => null,
            };
            if (parent is null)
            {
                continue;
            }

            var name = parent + "::" + Reader.GetString(member.Name);
            if (member.GetKind() == MemberReferenceKind.Method)
            {
                var method = member.DecodeMethodSignature(formatter, null);
                yield return (handle, name, method.ReturnType, FormatMethod(method));
            }
            else
            {
                var field = member.DecodeFieldSignature(formatter, null);
                yield return (handle, name, field, field);
            }
        }
    }

    private static string FormatMethod(MethodSignature<string> signature) =>
        signature.ReturnType + " (" + string.Join(", ", signature.ParameterTypes) + ")";

    /// <summary>The methods of the core (as Type.Method) whose bodies use the member reference <paramref name="member"/>.</summary>
    public IEnumerable<string> MethodsUsing(MemberReferenceHandle member)
    {
        foreach (var typeHandle in Reader.TypeDefinitions)
        {
            foreach (var methodHandle in Reader.GetTypeDefinition(typeHandle).GetMethods())
            {
                var method = Reader.GetMethodDefinition(methodHandle);
                if (method.RelativeVirtualAddress != 0
                    && Tokens(_pe.GetMethodBody(method.RelativeVirtualAddress)).Contains(member))
                {
                    yield return NameOf(typeHandle) + "." + Reader.GetString(method.Name);
                }
            }
        }
    }

    private void AddBody(MethodBodyBlock body, TypeCollector used)
    {
        if (!body.LocalSignature.IsNil)
        {
            var locals = Reader.GetStandaloneSignature(body.LocalSignature);
            _ = locals.DecodeLocalSignature(used, null);
        }

        foreach (var token in Tokens(body))
        {
            used.AddEntity(token);
        }
    }

    /// <summary>The metadata tokens (fields, methods, types, signatures) that a method body's IL names, in order.</summary>
    private static List<EntityHandle> Tokens(MethodBodyBlock body)
    {
        var tokens = new List<EntityHandle>();
        var il = body.GetILReader();
        while (il.RemainingBytes > 0)
        {
            ushort code = il.ReadByte();
            if (code == 0xFE)
            {
                code = (ushort)(0xFE00 | il.ReadByte());
            }

            switch (_operandTypes[code])
            {
                case OperandType.InlineField:
                case OperandType.InlineMethod:
                case OperandType.InlineType:
                case OperandType.InlineTok:
                case OperandType.InlineSig:
                    tokens.Add(MetadataTokens.EntityHandle(il.ReadInt32()));
                    break;
                case OperandType.InlineSwitch:
                    var cases = il.ReadInt32();
                    il.Offset += 4 * cases;
                    break;
                case OperandType.InlineI8:
                case OperandType.InlineR:
                    il.Offset += 8;
                    break;
                case OperandType.InlineBrTarget:
                case OperandType.InlineI:
                case OperandType.InlineString:
                case OperandType.ShortInlineR:
                    il.Offset += 4;
                    break;
                case OperandType.InlineVar:
                    il.Offset += 2;
                    break;
                case OperandType.ShortInlineBrTarget:
                case OperandType.ShortInlineI:
                case OperandType.ShortInlineVar:
                    il.Offset += 1;
                    break;
                case OperandType.InlineNone:
                    break;
                default:
                    throw new InvalidOperationException($"Unknown operand type of IL opcode 0x{code:X}.");
            }
        }

        return tokens;
    }

    /// <summary>Collects the type definitions named by signatures and tokens (a signature provider used for its side effect).</summary>
    private sealed class TypeCollector : ISignatureTypeProvider<int, object?>
    {
        private readonly MetadataReader _reader;

        public TypeCollector(MetadataReader reader)
        {
            _reader = reader;
        }

        public HashSet<TypeDefinitionHandle> Types { get; } = new();

        public void AddEntity(EntityHandle handle)
        {
            switch (handle.Kind)
            {
                case HandleKind.TypeDefinition:
                    Types.Add((TypeDefinitionHandle)handle);
                    break;
                case HandleKind.TypeSpecification:
                    _reader.GetTypeSpecification((TypeSpecificationHandle)handle).DecodeSignature(this, null);
                    break;
                case HandleKind.FieldDefinition:
                    Types.Add(_reader.GetFieldDefinition((FieldDefinitionHandle)handle).GetDeclaringType());
                    break;
                case HandleKind.MethodDefinition:
                    Types.Add(_reader.GetMethodDefinition((MethodDefinitionHandle)handle).GetDeclaringType());
                    break;
                case HandleKind.MemberReference:
                    var member = _reader.GetMemberReference((MemberReferenceHandle)handle);
                    AddEntity(member.Parent);
                    if (member.GetKind() == MemberReferenceKind.Method)
                    {
                        member.DecodeMethodSignature(this, null);
                    }
                    else
                    {
                        member.DecodeFieldSignature(this, null);
                    }

                    break;
                case HandleKind.MethodSpecification:
                    var specification = _reader.GetMethodSpecification((MethodSpecificationHandle)handle);
                    AddEntity(specification.Method);
                    specification.DecodeSignature(this, null);
                    break;
                case HandleKind.StandaloneSignature:
                    var signature = _reader.GetStandaloneSignature((StandaloneSignatureHandle)handle);
                    if (signature.GetKind() == StandaloneSignatureKind.Method)
                    {
                        signature.DecodeMethodSignature(this, null);
                    }

                    break;
            }
        }

        public int GetTypeFromDefinition(MetadataReader reader, TypeDefinitionHandle handle, byte rawTypeKind)
        {
            Types.Add(handle);
            return 0;
        }

        public int GetArrayType(int elementType, ArrayShape shape) => 0;

        public int GetByReferenceType(int elementType) => 0;

        public int GetFunctionPointerType(MethodSignature<int> signature) => 0;

        public int GetGenericInstantiation(int genericType, ImmutableArray<int> typeArguments) => 0;

        public int GetGenericMethodParameter(object? genericContext, int index) => 0;

        public int GetGenericTypeParameter(object? genericContext, int index) => 0;

        public int GetModifiedType(int modifier, int unmodifiedType, bool isRequired) => 0;

        public int GetPinnedType(int elementType) => 0;

        public int GetPointerType(int elementType) => 0;

        public int GetPrimitiveType(PrimitiveTypeCode typeCode) => 0;

        public int GetSZArrayType(int elementType) => 0;

        public int GetTypeFromReference(MetadataReader reader, TypeReferenceHandle handle, byte rawTypeKind) => 0;

        public int GetTypeFromSpecification(MetadataReader reader, object? genericContext, TypeSpecificationHandle handle, byte rawTypeKind) =>
            reader.GetTypeSpecification(handle).DecodeSignature(this, genericContext);
    }

    /// <summary>Writes signatures as text, ILDasm style, modifiers included (modreq(...) marks a ref readonly return).</summary>
    private sealed class SignatureFormatter : ISignatureTypeProvider<string, object?>
    {
        public string GetTypeFromReference(MetadataReader reader, TypeReferenceHandle handle, byte rawTypeKind)
        {
            var type = reader.GetTypeReference(handle);
            var ns = reader.GetString(type.Namespace);
            return (ns.Length > 0 ? ns + "." : string.Empty) + reader.GetString(type.Name);
        }

        public string GetTypeFromDefinition(MetadataReader reader, TypeDefinitionHandle handle, byte rawTypeKind)
        {
            var type = reader.GetTypeDefinition(handle);
            return reader.GetString(type.Namespace) + "." + reader.GetString(type.Name);
        }

        public string GetArrayType(string elementType, ArrayShape shape) => elementType + "[" + new string(',', shape.Rank - 1) + "]";

        public string GetByReferenceType(string elementType) => elementType + "&";

        public string GetFunctionPointerType(MethodSignature<string> signature) => "method " + FormatMethod(signature);

        public string GetGenericInstantiation(string genericType, ImmutableArray<string> typeArguments) =>
            genericType + "<" + string.Join(", ", typeArguments) + ">";

        public string GetGenericMethodParameter(object? genericContext, int index) => "!!" + index;

        public string GetGenericTypeParameter(object? genericContext, int index) => "!" + index;

        public string GetModifiedType(string modifier, string unmodifiedType, bool isRequired) =>
            unmodifiedType + (isRequired ? " modreq(" : " modopt(") + modifier + ")";

        public string GetPinnedType(string elementType) => elementType + " pinned";

        public string GetPointerType(string elementType) => elementType + "*";

        public string GetPrimitiveType(PrimitiveTypeCode typeCode) => typeCode.ToString();

        public string GetSZArrayType(string elementType) => elementType + "[]";

        public string GetTypeFromSpecification(MetadataReader reader, object? genericContext, TypeSpecificationHandle handle, byte rawTypeKind) =>
            reader.GetTypeSpecification(handle).DecodeSignature(this, genericContext);
    }
}
